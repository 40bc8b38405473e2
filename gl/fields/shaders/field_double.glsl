// Spell the texts core shares with C++ in double precision
// (triangle_distance.glsl, column_crossing.glsl) in GLSL; C++ spells them in
// their headers (svo/core/triangle_distance.h, svo/core/column_crossing.h).
#define SVO_FN
#define svo_dvec3 dvec3
#define SVO_INOUT(T) inout T
#define SVO_DOUBLE(x) x##LF
#define SVO_PRECISE precise
