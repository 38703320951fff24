// Core-profile entry point (headless tests): gl_FragCoord grows upwards, so flip y to
// match LÖVE's screen coordinates.
void main() {
    loadUniforms();
    fragColor = vec4(render(vec2(gl_FragCoord.x, uResolution.y - gl_FragCoord.y)), 1.0);
}
