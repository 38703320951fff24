// Glow: a miss brightens with the steps its ray took, so silhouettes get a halo.
background += vec3(float(steps) / 100.0);
