// Materials that are part mirrors (these lines go into the bounce loop of reflect.glsl
// only in scenes that have one): each bounce is mixed with the colour before it by
// the mirror amount of the surface the ray leaves (1: the article's bounce, 0: none).
// mapColor leaves the mirror amount of what it found in gMirror.
// @part start
float mirror = gMirror;
// @part before
if (mirror <= 0.0) {
    break;
}
vec3 before = color;
// @part mix
color = mix(before, color, mirror);
// @part next
mirror = gMirror;
