// benchmark: the same scene as spheres.scene
global_settings { max_trace_level 5 assumed_gamma 1 ambient_light rgb 1 }
camera { location <0,2.2,-7> look_at <0,0.8,0> angle 50 right x*4/3 }
light_source { <6,9,-7> color rgb 1 }
plane { y, 0 pigment { checker color rgb 0.9 color rgb 0.1 scale 0.5 } finish { ambient 0.15 diffuse 1 } }
sphere { <-1.6,1,0>, 1 pigment { rgb 0.1 } finish { ambient 0.15 diffuse 1 specular 0.9 roughness 1/120 reflection 0.8 } }
sphere { <1.3,0.9,-0.8>, 0.9 pigment { rgbt <0.02,0.02,0.02,0.9> } finish { ambient 0 diffuse 1 specular 0.9 roughness 1/200 reflection 0.08 } interior { ior 1.5 } }
sphere { <0.2,0.5,1.8>, 0.5 pigment { rgb <0.8,0.15,0.1> } finish { ambient 0.15 diffuse 1 specular 0.4 roughness 1/30 } }
