#version 450
// An array of three combined image samplers indexed by constants, plus a uniform block array.
layout(set = 0, binding = 0) uniform sampler2D texs[3];
layout(set = 0, binding = 2) uniform U { vec4 scale; } u[2];
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() {
    vec2 uv = v_color.xy;
    o = texture(texs[0], uv) * u[0].scale + texture(texs[2], uv.yx) * u[1].scale + texture(texs[1], uv * 2.0) * 0.125;
}
