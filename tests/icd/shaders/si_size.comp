#version 450
// imageSize of a level/layer view of a 2D array and of one level of a 2D image, and a load from the array's
// second layer of the view.
layout(local_size_x = 1) in;
layout(rgba8, set = 0, binding = 0) uniform readonly image2DArray arr;
layout(rgba8, set = 0, binding = 1) uniform readonly image2D lvl;
layout(std430, set = 0, binding = 2) buffer Out { ivec4 size_arr; ivec4 size_lvl; vec4 texel; } o;
void main() {
    o.size_arr = ivec4(imageSize(arr), 0);
    o.size_lvl = ivec4(imageSize(lvl), 0, 0);
    o.texel = imageLoad(arr, ivec3(1, 2, 1));
}
