#version 450
// ab_tex_array.frag with the uniform block array indexed by push constants (dynamically uniform), plus a storage
// buffer array read at a push-constant index.
layout(set = 0, binding = 0) uniform sampler2D texs[3];
layout(set = 0, binding = 2) uniform U { vec4 scale; } u[2];
layout(set = 0, binding = 3, std430) readonly buffer B { vec4 add; } b[2];
layout(push_constant) uniform P { int u0, u1, b0; } pc;
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() {
    vec2 uv = v_color.xy;
    o = texture(texs[0], uv) * u[pc.u0].scale + texture(texs[2], uv.yx) * u[pc.u1].scale +
        texture(texs[1], uv * 2.0) * 0.125 + b[pc.b0].add;
}
