// benchmark: the same scene as lights.scene, pattern for pattern
global_settings { max_trace_level 5 assumed_gamma 1 ambient_light rgb 0.5 }
camera { location <0,3,-7> look_at <0,0.8,0> angle 50 right x*4/3 }
light_source { <-5,8,-6> color rgb 0.5 fade_distance 10 fade_power 2 }
light_source { <4,6,-4> color rgb 0.4 spotlight point_at <0,0.5,0> radius 25 falloff 30 tightness 4 }
light_source { <-0.3,1,-0.4>*1000 color rgb 0.2 parallel point_at <0,0,0> }
light_source { <0,6,-1> color rgb 0.5 area_light <2,0,0>, <0,0,2>, 4, 4 jitter }
plane { y, 0 pigment { checker color rgb 0.9 color rgb 0.1 scale 0.5 } finish { ambient 0.15 diffuse 1 } }
sphere { <-2,1,0>, 1 pigment { marble turbulence 1.2 octaves 6 frequency 2
    color_map { [0 rgb <0.95,0.94,0.9>] [0.6 rgb <0.7,0.7,0.72>] [1 rgb <0.3,0.3,0.35>] } }
  finish { ambient 0.15 diffuse 0.9 specular 0.6 roughness 1/60 } }
box { <-0.6,0,-0.6>, <0.6,1.2,0.6> pigment { wood turbulence 0.05 octaves 4 frequency 6 rotate <90,0,0>
    color_map { [0 rgb <0.55,0.33,0.16>] [1 rgb <0.35,0.2,0.08>] } }
  finish { ambient 0.15 diffuse 0.8 specular 0.3 roughness 1/20 } rotate <0,25,0> translate <0.3,0,1.2> }
cylinder { <0,0,0>, <0,1.6,0>, 0.5 pigment { granite octaves 6 scale 2
    color_map { [0 rgb <0.2,0.18,0.17>] [0.5 rgb <0.6,0.55,0.5>] [1 rgb <0.9,0.88,0.85>] } }
  finish { ambient 0.15 diffuse 0.9 } translate <2.2,0,0.3> }
torus { 0.6, 0.25 pigment { rgb <0.8,0.15,0.1> } finish { ambient 0.15 diffuse 1 specular 0.4 roughness 1/30 }
  translate <0.4,0.25,-1.4> }
