#version 450
// A block member struct copied into a local struct: SPIR-V 1.4+ makes that one OpCopyLogical (the two structs differ
// in layout decorations only). Compiled for Vulkan 1.2; ApiVulkan12.Spirv15CopyLogicalAndIntegerTextures.
struct Tint {
    vec4 mul;
    vec4 add;
};
layout(push_constant) uniform PC { layout(offset = 16) Tint t; } pc;
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() {
    Tint t = pc.t;
    o = v_color * t.mul + t.add;
}
