// The player's moving picture, before it is stretched to the window (src/app/play.fnl's
// draw-stretched): a pixel brighter or darker than all four of its neighbours, in any
// channel (a firefly that one ray found: a glint between two tiles, a speck of a
// reflected horizon), is clamped to their range, so the linear stretch does not blow
// it up into a blob. A pixel on an edge or a line lies within its neighbours' range
// and keeps its value. Drawn canvas to canvas at the same size: uv is a texel's centre.
uniform vec2 texelSize;

vec4 effect(vec4 color, Image tex, vec2 uv, vec2 screen) {
    vec4 c = Texel(tex, uv);
    // On the picture's border the missing neighbour is the one across (a neighbour
    // outside would read the pixel itself, and keep a firefly there).
    float dx = texelSize.x;
    float dy = texelSize.y;
    vec4 east = Texel(tex, uv + vec2(uv.x + dx > 1.0 ? -dx : dx, 0.0));
    vec4 west = Texel(tex, uv + vec2(uv.x - dx < 0.0 ? dx : -dx, 0.0));
    vec4 north = Texel(tex, uv + vec2(0.0, uv.y + dy > 1.0 ? -dy : dy));
    vec4 south = Texel(tex, uv + vec2(0.0, uv.y - dy < 0.0 ? dy : -dy));
    vec4 lo = min(min(east, west), min(north, south));
    vec4 hi = max(max(east, west), max(north, south));
    return clamp(c, lo, hi) * color;
}
