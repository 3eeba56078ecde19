#version 450
layout(location = 0) in vec4 v_smooth;
layout(location = 1) noperspective in vec4 v_linear;
layout(location = 2) flat in vec4 v_flat;
layout(location = 0) out vec4 o;
layout(push_constant) uniform PC { int mode; } pc;
void main() {
    int sel = pc.mode & 3;
    o = sel == 0 ? v_smooth : (sel == 1 ? v_linear : v_flat);
    // amplified mode: exact x*2^16 then fract (x - floor(x), exact), so one-ulp differences reach the u8 output
    if ((pc.mode & 4) != 0) o = fract(o * 65536.0);
    // depth mode: the interpolated window z with lavapipe's depth offset, low bits exposed
    if ((pc.mode & 8) != 0) {
        float z = gl_FragCoord.z;
        o = vec4(fract(z * 65536.0), fract(z * 256.0), z, fract(z * 16777216.0));
    }
}
