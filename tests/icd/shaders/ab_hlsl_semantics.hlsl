// VK_GOOGLE_hlsl_functionality1 / VK_GOOGLE_decorate_string: glslang -fhlsl_functionality1 keeps the HLSL semantic
// names as OpDecorateString UserSemantic decorations, which change nothing: the colour is a function of the pixel
// centre and the blue of ab_fullscreen.vert's constant 0.75, (frac((x + 0.5) / 8), frac((y + 0.5) / 8), 0.75, 1).
struct PixelIn {
    float4 position : SV_Position;
    [[vk::location(0)]] float4 colour : COLOR0;
};

float4 main(PixelIn i) : SV_Target0 {
    return float4(frac(i.position.x / 8.0), frac(i.position.y / 8.0), i.colour.z, 1.0);
}
