// placeholder until the scenes module lands
