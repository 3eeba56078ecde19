#version 450
// VK_KHR_shader_terminate_invocation: pixels of odd x ^ y end their invocation; the others write their position.
#extension GL_EXT_terminate_invocation : require
layout(location = 0) in vec4 v_color;  // ab_fullscreen.vert's output, consumed (adds 0)
layout(location = 0) out vec4 o;
void main() {
    if (((int(gl_FragCoord.x) ^ int(gl_FragCoord.y)) & 1) != 0) terminateInvocation;
    o = vec4(gl_FragCoord.xy, 0.25, 1.0) + v_color * 0.0;
}
