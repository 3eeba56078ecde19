#version 450
// A loop that never ends (i stays non-negative); its result feeds the position so no optimizer may drop it.
layout(location = 0) in vec4 pos;
layout(location = 1) in vec4 color;
layout(location = 0) out vec4 v_color;
void main() {
    int i = 0;
    while (i >= 0) i = (i + 1) & 0x7fff;
    gl_Position = pos + vec4(float(i) * 1e-9);
    v_color = color;
}
