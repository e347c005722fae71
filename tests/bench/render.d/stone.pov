// benchmark: the same scene as stone.scene, pattern for pattern
global_settings { max_trace_level 5 assumed_gamma 1 ambient_light rgb 1 }
camera { location <0,2.5,-7> look_at <0,1,0> angle 50 right x*4/3 }
light_source { <-4,7,-6> color rgb 1 fade_distance 10 fade_power 2 }
light_source { <3,6,-5> color rgb 0.6 spotlight point_at <0,0.8,0> radius 25 falloff 30 tightness 4 }
#declare Granite = texture {
  pigment { granite
    color_map { [0 rgb 0.25] [1 rgb 0.85] } }
  finish { ambient 0.15 diffuse 0.8 specular 0.3 roughness 1/30 } }
plane { y, 0 texture { Granite } }
plane { z, 3
  pigment { brick color rgb <0.85,0.82,0.76> color rgb <0.66,0.27,0.18> brick_size <0.5,0.25,0.5> mortar 0.03 }
  normal { brick 0.3 brick_size <0.5,0.25,0.5> mortar 0.03 }
  finish { ambient 0.15 diffuse 1 } }
intersection { sphere { <0,1,0>, 1 } box { <-0.8,0.2,-0.8>, <0.8,1.8,0.8> }
  pigment { marble turbulence 1.2 octaves 6 omega 0.5 lambda 2 frequency 2
    color_map { [0 rgb <0.95,0.94,0.9>] [0.6 rgb <0.7,0.7,0.72>] [1 rgb <0.3,0.3,0.35>] } }
  finish { ambient 0.15 diffuse 0.9 specular 0.6 roughness 1/60 } rotate <0,30,0> translate <-1.8,0,0> }
sphere { <1.8,0.9,0>, 0.9 texture { Granite } }
