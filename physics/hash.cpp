// placeholder until the physics module lands
