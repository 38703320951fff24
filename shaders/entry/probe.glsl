// Probe entry point (`love . --probe SCENE --gpu`): pixel (x, y) evaluates the scene at
// the world point stored in the same texel of uPoints (the camera sits at the world's
// origin for probing). uProbeChannel 0 writes (distance, colour), 1 the mirror amount.
uniform sampler2D uPoints;
uniform int uProbeChannel;

vec4 effect(vec4 vertexColor, Image tex, vec2 texCoord, vec2 screenCoord) {
    loadUniforms();
    vec3 p = texelFetch(uPoints, ivec2(screenCoord), 0).xyz;
    vec3 color;
    float d = mapColor(p, color);
    // @slot mirror
}
