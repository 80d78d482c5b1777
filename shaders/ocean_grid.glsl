// One vertex of the projected grid, as shaders/ocean_grid.comp writes it (std430).
struct OceanGridVertex {
  vec4 world;   // xyz: the displaced water, metres; w: the Jacobian J
  vec4 normal;  // xyz: unit; w: the grid's spacing there, metres
  vec4 rest;    // xy: where the water rests, (x, z)
};
