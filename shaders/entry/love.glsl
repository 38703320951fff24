// LÖVE entry point: screenCoord is in pixels with y growing downwards.
vec4 effect(vec4 vertexColor, Image tex, vec2 texCoord, vec2 screenCoord) {
    loadUniforms();
    return vec4(render(screenCoord), 1.0);
}
