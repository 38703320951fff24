// Common uniforms. The camera sits at the origin: every position the shader sees was
// made camera-relative on the CPU, in double precision, before upload.
uniform vec2 uResolution;     // render target size in pixels
uniform vec3 uCamForward;     // camera basis (the article's: right = cross(-z, forward))
uniform vec3 uCamRight;
uniform vec3 uCamUp;          // points down the screen, as pixel y grows downwards
uniform float uProjDist;      // 1 / tan(fov / 2)
uniform vec3 uLightPos;
uniform vec3 uEnvColor;
uniform int uMaxSteps;
uniform float uEpsilon;       // hit test: world units, or a fraction (see hitThreshold)
uniform float uDrawDist;
// @slot feature-uniforms

// 0, set by loadUniforms from a value the compiler cannot fold. A loop that starts
// from it is kept as a loop: a call inside it is compiled once, not once per turn
// (normals: four to six scene evaluations each).
int gZero = 0;

// True while the field is read as an estimate of the distance (a soft shadow's
// penumbra, occlusion) rather than stepped by: an argument the tape marks so takes its
// estimate's value then (a custom node declared steeper than it measured).
bool gEstimate = false;
