// benchmark: the same scene as csg.scene
global_settings { max_trace_level 5 assumed_gamma 1 ambient_light rgb 1 }
camera { location <0,3,-7> look_at <0,0.8,0> angle 50 right x*4/3 }
light_source { <-5,8,-6> color rgb 1 }
plane { y, 0 pigment { checker color rgb 0.9 color rgb 0.1 scale 0.5 } finish { ambient 0.15 diffuse 1 } }
difference { box { <-1,0,-1>, <1,2,1> } sphere { <0,1,0>, 1.3 }
  pigment { checker color rgb <0.81,0.54,0.18> color rgb <0.27,0.18,0.06> scale 0.5 }
  finish { ambient 0.15 diffuse 1 specular 0.5 roughness 1/40 } translate <-2,0,0> }
intersection { sphere { <0,1,0>, 1.2 } box { <-1,0,-1>, <1,2,1> } pigment { rgb <0.2,0.3,0.8> }
  finish { ambient 0.15 diffuse 1 specular 0.8 roughness 1/80 reflection 0.4 } rotate <0,30,0> }
difference { cylinder { <0,0,0>, <0,2,0>, 0.8 } cylinder { <0,0.3,0>, <0,2.5,0>, 0.6 }
  pigment { checker color rgb <0.81,0.54,0.18> color rgb <0.27,0.18,0.06> scale 0.25 }
  finish { ambient 0.15 diffuse 1 specular 0.5 roughness 1/40 } translate <2.2,0,0.5> }
