#version 450
// VK_KHR_shader_non_semantic_info: NonSemantic.DebugPrintf instructions (and their OpString) beside ordinary ones;
// they have no semantics, so the output is the constant (0.2, 0.4, 0.8, 1).
#extension GL_EXT_debug_printf : require
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 o;
void main() {
    debugPrintfEXT("colour %f %f", v_color.x, v_color.y);
    o = vec4(0.2, 0.4, 0.8, 1.0);
    debugPrintfEXT("written");
}
