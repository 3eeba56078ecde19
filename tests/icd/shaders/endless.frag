#version 450
// A loop that never ends (i stays non-negative); its result feeds the colour so no optimizer may drop it.
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() {
    int i = 0;
    while (i >= 0) i = (i + 1) & 0x7fff;
    o = v_color + vec4(float(i) * 1e-9);
}
