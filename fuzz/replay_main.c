/* replay_main.c - main() for fuzz targets built without libFuzzer: runs
 * LLVMFuzzerTestOneInput on every regular file of the directories (or on the files) named
 * on the command line, in name order, and ends with the plain line "N passed, 0 failed".
 * A target reports a broken invariant by aborting; the signal handler then names the file
 * and prints "N passed, 1 failed" before exiting non-zero. No input at all is a failure
 * too, so a mistyped corpus path cannot pass. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char current[4096];
static volatile sig_atomic_t passed;

static void put(const char *s) { (void)!write(2, s, strlen(s)); }

static void on_crash(int sig)
{
    char num[24];
    int n = 0, v = (int)passed;
    put("\nreplay: FAILED (signal ");
    put(sig == SIGABRT ? "SIGABRT" : sig == SIGSEGV ? "SIGSEGV" : sig == SIGFPE ? "SIGFPE" : "other");
    put(") on input: ");
    put(current);
    put("\n");
    do num[n++] = (char)('0' + v % 10); while ((v /= 10) > 0);
    while (n > 0) (void)!write(1, &num[--n], 1);
    (void)!write(1, " passed, 1 failed\n", 18);
    _exit(1);
}

static int run_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    uint8_t *buf;
    long size;
    if (!f || fseek(f, 0, SEEK_END) != 0 || (size = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fprintf(stderr, "replay: cannot read %s\n", path);
        if (f) fclose(f);
        return 0;
    }
    /* Exactly `size` bytes, so a sanitizer build catches reads past the input. */
    buf = (uint8_t *)malloc(size ? (size_t)size : 1u);
    if (!buf || fread(buf, 1, (size_t)size, f) != (size_t)size) {
        fprintf(stderr, "replay: cannot read %s\n", path);
        free(buf);
        fclose(f);
        return 0;
    }
    fclose(f);
    snprintf(current, sizeof current, "%s", path);
    LLVMFuzzerTestOneInput(buf, (size_t)size);
    free(buf);
    passed++;
    return 1;
}

int main(int argc, char **argv)
{
    static const int sigs[] = {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL};
    int a, bad = 0;
    size_t s;
    for (s = 0; s < sizeof sigs / sizeof sigs[0]; s++) signal(sigs[s], on_crash);
    if (argc < 2) {
        fprintf(stderr, "usage: %s CORPUS_DIR_OR_FILE...\n", argv[0]);
        return 2;
    }
    for (a = 1; a < argc; a++) {
        struct stat st;
        struct dirent **list;
        int n, i;
        if (stat(argv[a], &st) != 0) {
            fprintf(stderr, "replay: %s does not exist\n", argv[a]);
            bad++;
            continue;
        }
        if (!S_ISDIR(st.st_mode)) {
            bad += !run_file(argv[a]);
            continue;
        }
        if ((n = scandir(argv[a], &list, NULL, alphasort)) < 0) {
            fprintf(stderr, "replay: cannot list %s\n", argv[a]);
            bad++;
            continue;
        }
        for (i = 0; i < n; i++) {
            char path[4096];
            snprintf(path, sizeof path, "%s/%s", argv[a], list[i]->d_name);
            if (stat(path, &st) == 0 && S_ISREG(st.st_mode)) bad += !run_file(path);
            free(list[i]);
        }
        free(list);
    }
    if (passed == 0) {
        fprintf(stderr, "replay: no inputs found\n");
        bad++;
    }
    printf("%d passed, %d failed\n", (int)passed, bad);
    return bad ? 1 : 0;
}
