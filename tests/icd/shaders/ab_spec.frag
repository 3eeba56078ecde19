#version 450
// Specialization constants of three types, one of them sizing an array.
layout(constant_id = 0) const float scale = 1.0;
layout(constant_id = 3) const int mode = 0;
layout(constant_id = 7) const bool invert = false;
layout(constant_id = 9) const int count = 2;
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() {
    float w[count];
    for (int i = 0; i < count; ++i) w[i] = float(i + 1) / float(count);
    vec4 c = v_color * scale * w[count - 1];
    if (mode == 1) c = c.bgra;
    else if (mode == 2) c = vec4(c.r);
    o = invert ? vec4(1.0) - c : c;
}
