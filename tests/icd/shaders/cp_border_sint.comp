#version 450
// VK_EXT_custom_border_color: one lookup at level 0 per invocation (api_breadth_sampler_test.cpp), the result's
// bits stored as they are.
layout(local_size_x = 16) in;
layout(set = 0, binding = 0) uniform isampler2D tex;
layout(set = 0, binding = 1, std430) readonly buffer Coords { vec2 coords[]; };
layout(set = 0, binding = 2, std430) writeonly buffer Out { ivec4 o[]; };
void main() {
    const uint i = gl_GlobalInvocationID.x;
    o[i] = textureLod(tex, coords[i], 0.0);
}
