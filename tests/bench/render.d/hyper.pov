// benchmark: the same scene as hyper.scene: a ball of density 1 - r^2 times 6-octave
// turbulence (POV-Ray's granite: a sum of |noise| over octaves, 4 cells a unit, scaled to
// 2) absorbing, emitting and scattering the point light, which the media attenuates on its
// way (media_attenuation); method 3, one interval of 10 samples
global_settings { max_trace_level 5 assumed_gamma 1 ambient_light rgb 0.3 }
background { rgb <0.1,0.1,0.15> }
camera { location <0,1.5,-5> look_at <0,0.9,0> angle 50 right x*4/3 }
light_source { <-4,6,-4> color rgb 1 media_attenuation on }
plane { y, 0 pigment { rgb 0.7 } finish { ambient 0.3 diffuse 1 } }
sphere { 0, 1 pigment { rgbt 1 } hollow
  interior { media {
    method 3 intervals 1 samples 10
    absorption 1
    scattering { 1, 2 }
    emission <0.3,0.15,0.05>
    density { function { max(0, 1 - (x * x + y * y + z * z)) } }
    density { granite scale 2 color_map { [0 rgb 0] [1 rgb 5] } }
  } }
  translate <0,1,0> }
