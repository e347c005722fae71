#version 3.7;
// five_spheres.pov - POV-Ray 3.7 equivalent of patterns/five_spheres.scene as
// rendered by `t_apply --rgb --model phong` (Whitted-Phong, RGB): same camera,
// two point lights, five spheres of radius 0.8, a checkered plane (1-unit
// checks), the same ambient, diffuse, Phong, reflection and refraction terms,
// trace depth 5.  For tests/bench/render_spectral.
global_settings { max_trace_level 5 assumed_gamma 1 ambient_light rgb 0.25 }
camera { location <0, 2.2, -7> look_at <0, 0.7, 0> angle 60 right x*4/3 }
background { rgb <0.02, 0.02, 0.03> }
light_source { <-5, 9, -7> color rgb 0.9 }
light_source { <6, 6, -4> color rgb 0.35 }
plane { y, 0
    pigment { checker color rgb 0.755 color rgb 0.155 }
    finish { ambient 0.3 diffuse 1 specular 0.5 roughness 1/40 reflection 0.35 } }
#macro Metal(P, C)
    sphere { P, 0.8 pigment { rgb C }
        finish { ambient 0.2 diffuse 1 specular 0.7 roughness 1/60 reflection 0.8 } }
#end
sphere { <-3.2, 0.8, 0.6>, 0.8
    pigment { rgbt <0.02, 0.02, 0.02, 0.9> }
    finish { ambient 0 diffuse 1 specular 0.6 roughness 1/200 reflection 0.6 }
    interior { ior 1.5168 } }
Metal(<-1.6, 0.8, -0.4>, <0.72, 0.38, 0.24>)
Metal(<0, 0.8, 0.8>, <0.85, 0.65, 0.25>)
Metal(<1.6, 0.8, -0.4>, <0.75, 0.75, 0.75>)
Metal(<3.2, 0.8, 0.6>, <0.55, 0.55, 0.57>)
