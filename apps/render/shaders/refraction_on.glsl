// Prepended to the programs that bend the view rays at the water surface
// (Scene::view_refraction): refraction.glsl, fish.vert.glsl, tank.vert.glsl and the
// fragment shaders take the refracted path where it is defined.
#define FINFLEX_REFRACTION 1
