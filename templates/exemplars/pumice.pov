// Wangscape exemplar: pumice gravel, seen straight down (Side x Side units of ground).
// Render: see README.md in this folder.
#version 3.7;
global_settings { assumed_gamma 1.0 }

// 192 pixels per unit: rendered at 512 x 512 pixels, Side = 512 / 192 (a varied exemplar that
// holds many well-separated windows; issue 23).
#declare Side = 512 / 192;
camera { orthographic location <Side / 2, 5, Side / 2> look_at <Side / 2, 0, Side / 2> right <Side, 0, 0> up <0, 0, Side> }
light_source { <-3, 8, 4> color rgb <1.0, 0.97, 0.92> * 1.1 }
light_source { <4, 6, -2> color rgb <0.6, 0.62, 0.7> * 0.45 shadowless }

// Fine grey-beige grit between the stones.
plane { y, 0
  texture {
    pigment { granite scale 0.05
      color_map { [0.0 rgb <0.30, 0.28, 0.25>] [0.6 rgb <0.45, 0.42, 0.38>] [1.0 rgb <0.58, 0.55, 0.50>] } }
    normal { granite 0.5 scale 0.02 }
    finish { diffuse 0.85 ambient 0.05 }
  }
}

// Porous stones: flattened blobs of several sizes with cratered (crackle) surfaces.
#declare R = seed(1980);
#declare N = 0;
#while (N < 420 * Side * Side)
  #declare Size = 0.015 + 0.045 * pow(rand(R), 2);
  #declare Tone = rand(R);
  sphere { 0, 1
    scale <Size * (0.8 + 0.5 * rand(R)), Size * (0.45 + 0.3 * rand(R)), Size * (0.8 + 0.5 * rand(R))>
    rotate <0, 360 * rand(R), 0>
    translate <rand(R) * (Side + 0.2) - 0.1, 0, rand(R) * (Side + 0.2) - 0.1>
    texture {
      pigment { crackle scale Size * 0.4 turbulence 0.3
        color_map { [0.0 rgb <0.45, 0.43, 0.40> * (0.7 + 0.5 * Tone)] [0.15 rgb <0.72, 0.69, 0.63> * (0.7 + 0.5 * Tone)]
                    [1.0 rgb <0.80, 0.77, 0.70> * (0.7 + 0.5 * Tone)] } }
      normal { crackle -0.8 scale Size * 0.4 }
      finish { diffuse 0.85 ambient 0.05 }
    }
  }
  #declare N = N + 1;
#end
