#version 450
// VK_KHR_shader_draw_parameters: each draw's triangles go to a cell chosen by DrawIndex and the instance within the
// draw; the colour carries DrawIndex, BaseVertex and BaseInstance.
#extension GL_ARB_shader_draw_parameters : require
layout(location = 0) out vec4 v_color;
void main() {
    int local = (gl_VertexIndex - gl_BaseVertexARB) % 3;  // indexed draws: the index (0, 1, 2) + vertexOffset
    vec2 corner = vec2(local == 1 ? 1.0 : 0.0, local == 2 ? 1.0 : 0.0);
    float cell = float(gl_DrawIDARB * 4 + (gl_InstanceIndex - gl_BaseInstanceARB));
    vec2 origin = vec2(mod(cell, 4.0), floor(cell / 4.0)) * 0.5 - 1.0;
    gl_Position = vec4(origin + corner * 0.45, 0.5, 1);
    v_color = vec4(float(gl_DrawIDARB) / 8.0, float(gl_BaseVertexARB) / 64.0, float(gl_BaseInstanceARB) / 64.0, 1);
}
