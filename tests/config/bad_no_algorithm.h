/* bad_no_algorithm.h - a build with no algorithm; check_config.h must reject it (a CMake
 * build with an empty PN_ALGORITHMS defines every PN_ENABLE_<NAME> 0).
 * expect-error: PN_ALGORITHMS names no algorithm */
#define PN_ENABLE_REFERENCE 0
#define PN_ENABLE_GEARS 0
#define PN_ENABLE_RAYTRACE 0
#define PN_ENABLE_SRT 0
#define PN_ENABLE_OCCTEX 0
#define PN_ENABLE_MCSM 0
#define PN_ENABLE_WEDGES 0
