#version 450
// Several sets and bindings: uniform buffers (one dynamic), a combined image sampler, a separate texture + sampler.
layout(set = 0, binding = 0) uniform A { vec4 a; };
layout(set = 0, binding = 3) uniform sampler2D combined;
layout(set = 1, binding = 0) uniform B { vec4 b; };  // dynamic
layout(set = 1, binding = 1) uniform texture2D separate_tex;
layout(set = 1, binding = 2) uniform sampler separate_sampler;
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() {
    vec2 uv = v_color.xy;
    o = a * 0.25 + b * 0.25 + texture(combined, uv) * 0.25 + texture(sampler2D(separate_tex, separate_sampler), uv.yx) * 0.25;
}
