// benchmark: the same scene as workshop.scene, pattern for pattern
global_settings { max_trace_level 5 assumed_gamma 1 ambient_light rgb 1 }
camera { location <0,3,-6.5> look_at <0,0.7,0> angle 50 right x*4/3 }
light_source { <-5,8,-6> color rgb 1 fade_distance 10 fade_power 2 }
light_source { <2,6,-5> color rgb 0.7 spotlight point_at <0.5,0.5,0> radius 25 falloff 30 tightness 4 }
#declare Oak = texture {
  pigment { wood turbulence 0.05 octaves 4 frequency 6 rotate <90,0,0>
    color_map { [0 rgb <0.55,0.33,0.16>] [1 rgb <0.35,0.2,0.08>] } }
  finish { ambient 0.15 diffuse 0.7 specular 0.3 roughness 1/20 } }
plane { y, 0
  pigment { brick color rgb <0.85,0.82,0.76> color rgb <0.66,0.27,0.18> brick_size <0.5,0.25,0.5> mortar 0.03 }
  normal { brick 0.3 brick_size <0.5,0.25,0.5> mortar 0.03 }
  finish { ambient 0.15 diffuse 1 } }
box { <-2.6,0,-0.6>, <0.4,0.4,0.6> texture { Oak } rotate <0,20,0> }
cylinder { <0,0,0>, <0,2.2,0>, 0.35 texture { Oak } translate <-2.2,0,1.2> }
cone { <0,0,0>, 0.8, <0,2,0>, 0.3
  pigment { image_map { png "checker.png" map_type 2 } }
  finish { ambient 0.15 diffuse 1 specular 0.4 roughness 1/40 } translate <1.6,0,0> }
