#version 450
layout(location = 0) in vec4 smooth_attr;
layout(location = 1) noperspective in vec4 linear_attr;
layout(location = 0) out vec4 o;
void main() { o = vec4(smooth_attr.xy, linear_attr.xy); }
