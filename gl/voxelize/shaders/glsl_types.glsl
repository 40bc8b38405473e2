// Spell overlap.glsl's portable types in GLSL (C++ spells them in overlap.h).
#define SVO_FN
#define svo_real float
#define svo_vec3 vec3
