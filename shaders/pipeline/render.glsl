// The primary ray through a pixel (x right, y down, in pixels), the article's camera:
// uv x spans the aspect ratio, uv y spans [-0.5, 0.5] down the screen.
vec3 primaryRay(vec2 pixel) {
    vec2 uv = vec2((pixel.x / uResolution.x - 0.5) * (uResolution.x / uResolution.y),
                   pixel.y / uResolution.y - 0.5);
    return normalize(uCamForward * uProjDist + uCamRight * uv.x + uCamUp * uv.y);
}

vec3 @{render}(vec2 pixel) {
    vec3 ro = vec3(0.0);
    vec3 rd = primaryRay(pixel);
    int steps;
    // @slot primary
    // @slot adaptive
    // @slot view
}
