// Wangscape exemplar: meadow soil with grass, seen straight down (Side x Side units of ground).
// Render: see README.md in this folder.
#version 3.7;
global_settings { assumed_gamma 1.0 }

// 192 pixels per unit: rendered at 512 x 512 pixels, Side = 512 / 192 (a varied exemplar that
// holds many well-separated windows; issue 23).
#declare Side = 512 / 192;
camera { orthographic location <Side / 2, 5, Side / 2> look_at <Side / 2, 0, Side / 2> right <Side, 0, 0> up <0, 0, Side> }
light_source { <-3, 8, 4> color rgb <1.0, 0.97, 0.9> * 1.1 }
light_source { <4, 6, -2> color rgb <0.55, 0.6, 0.7> * 0.5 shadowless }

// Soil: brown earth with darker clods and small light grit.
plane { y, 0
  texture {
    pigment { granite turbulence 0.6 scale 0.35
      color_map { [0.0 rgb <0.20, 0.14, 0.08>] [0.5 rgb <0.32, 0.23, 0.13>] [0.8 rgb <0.26, 0.19, 0.11>]
                  [1.0 rgb <0.42, 0.33, 0.22>] } }
    normal { bumps 0.6 scale 0.012 }
    finish { diffuse 0.8 ambient 0.05 }
  }
}

// Grass: thin tapered blades leaning in random directions, several shades of green.
#declare R = seed(2026);
#declare Blade = cone { <0, 0, 0>, 0.006, <0, 0.12, 0>, 0.0005 }
#declare N = 0;
#while (N < 2600 * Side * Side)
  #declare X = rand(R) * (Side + 0.2) - 0.1;
  #declare Z = rand(R) * (Side + 0.2) - 0.1;
  #declare Patch = 0.5 + 0.5 * sin(X * 9.0 + 2.0 * cos(Z * 7.0));  // denser in patches
  #if (rand(R) < 0.35 + 0.65 * Patch)
    #declare Shade = rand(R);
    object { Blade
      scale <1, 0.5 + rand(R), 1>
      rotate <35 + 40 * rand(R), 0, 0>
      rotate <0, 360 * rand(R), 0>
      translate <X, 0, Z>
      texture {
        pigment { rgb <0.10 + 0.20 * Shade, 0.30 + 0.25 * Shade, 0.05 + 0.06 * Shade> }
        finish { diffuse 0.8 specular 0.15 roughness 0.05 ambient 0.06 }
      }
    }
  #end
  #declare N = N + 1;
#end
