// Shadertoy entry point (`love . --export-shader`): fragCoord grows upwards, so flip y
// to match the app's screen coordinates. Every value is baked in as a constant; only
// the resolution comes from the host.
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    uResolution = iResolution.xy;
    loadUniforms();
    fragColor = vec4(render(vec2(fragCoord.x, iResolution.y - fragCoord.y)), 1.0);
}
