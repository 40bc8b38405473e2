/* LD_PRELOAD shim for no_gl.sh where no mount namespace can be had (a
 * container that forbids unshare): dlopen refuses the GL and EGL libraries,
 * as on a machine without them. svo links none of them (no_gl.sh checks
 * that with ldd), so dlopen is the only way they could come in. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <string.h>

static int isGl(const char* file)
{
    static const char* const prefixes[] = {"libEGL", "libOpenGL.", "libGL.", "libGLX", "libGLdispatch", "libGLES"};
    const char* base = strrchr(file, '/');
    base = base ? base + 1 : file;
    for (size_t i = 0; i < sizeof prefixes / sizeof prefixes[0]; ++i)
        if (strncmp(base, prefixes[i], strlen(prefixes[i])) == 0) return 1;
    return 0;
}

void* dlopen(const char* file, int mode)
{
    static void* (*real)(const char*, int);
    if (!real) real = (void* (*)(const char*, int))dlsym(RTLD_NEXT, "dlopen");
    if (file && isGl(file)) return NULL;
    return real(file, mode);
}
