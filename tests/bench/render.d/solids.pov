// benchmark: the same scene as solids.scene, pattern for pattern
global_settings { max_trace_level 5 assumed_gamma 1 ambient_light rgb 1 }
camera { location <0,3.2,-6> look_at <0,0.4,1.4> angle 50 right x*4/3 }
light_source { <-5,8,-6> color rgb 1 }
light_source { <4,7,-4> color rgb 0.5 spotlight point_at <0,0,1.4> radius 30 falloff 35 tightness 2 }
plane { y, 0 pigment { checker color rgb 0.9 color rgb 0.1 scale 0.5 } finish { ambient 0.15 diffuse 1 } }
#declare F = finish { ambient 0.15 diffuse 0.9 }
#declare S = finish { ambient 0.15 diffuse 0.9 specular 0.5 roughness 1/30 }
sphere { <-2.4,0.5,0>, 0.5 pigment { marble turbulence 1.2 octaves 6 frequency 2
    color_map { [0 rgb <0.95,0.94,0.9>] [0.6 rgb <0.7,0.7,0.72>] [1 rgb <0.3,0.3,0.35>] } }
  finish { ambient 0.15 diffuse 0.9 specular 0.6 roughness 1/60 } }
sphere { <-0.8,0.5,0>, 0.5 pigment { wood turbulence 0.05 octaves 4 frequency 6 rotate <90,0,0>
    color_map { [0 rgb <0.55,0.33,0.16>] [1 rgb <0.35,0.2,0.08>] } }
  finish { ambient 0.15 diffuse 0.8 specular 0.3 roughness 1/20 } }
sphere { <0.8,0.5,0>, 0.5 pigment { granite octaves 6 scale 2
    color_map { [0 rgb <0.2,0.18,0.17>] [0.5 rgb <0.6,0.55,0.5>] [1 rgb <0.9,0.88,0.85>] } } finish { F } }
sphere { <2.4,0.5,0>, 0.5 pigment { bozo scale 0.5
    color_map { [0 rgb <1,0,0>] [0.33 rgb <1,1,0>] [0.66 rgb <0,1,0>] [1 rgb <0,0,1>] } } finish { F } }
sphere { <-2.4,0.5,1.4>, 0.5 pigment { crackle scale 0.2
    color_map { [0 rgb <0,0,0.05>] [0.5 rgb <0.7,0.2,0.5>] [1 rgb <1,0.9,0.6>] } } finish { F } }
sphere { <-0.8,0.5,1.4>, 0.5 pigment { agate agate_turb 0.5
    color_map { [0 rgb <0.3,0.5,0.2>] [0.5 rgb <0.9,0.9,0.8>] [1 rgb <0.2,0.3,0.6>] } }
  finish { ambient 0.15 diffuse 0.9 specular 0.4 roughness 1/40 } }
sphere { <0.8,0.5,1.4>, 0.5 pigment { spotted scale 0.2
    color_map { [0 rgb <0.1,0,0.5>] [0.5 rgb <0.8,0.3,0.5>] [1 rgb <1,1,0.2>] } } finish { F } }
sphere { <2.4,0.5,1.4>, 0.5 pigment { rgb <0.8,0.5,0.3> } normal { bumps 0.4 scale 0.17 } finish { S } }
sphere { <-2.4,0.5,2.8>, 0.5 pigment { rgb <0.3,0.5,0.8> } normal { wrinkles 0.5 scale 0.25 } finish { S } }
sphere { <-0.8,0.5,2.8>, 0.5 pigment { leopard scale 0.08
    color_map { [0 rgb <0.1,0,0>] [0.5 rgb <0.9,0.3,0>] [1 rgb <1,1,0.5>] } } finish { F } }
sphere { <0.8,0.5,2.8>, 0.5 pigment { onion scale 0.25
    color_map { [0 rgb <0.2,0.4,0.8>] [1 rgb <0.9,0.95,1>] } } finish { F } }
sphere { <2.4,0.5,2.8>, 0.5 pigment { gradient y turbulence 0.5 octaves 3 scale 0.5
    color_map { [0 rgb <0.2,0.4,0.8>] [1 rgb <0.9,0.95,1>] } } finish { F } }
