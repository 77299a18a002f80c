/* replay_main.c - main() for fuzz targets built without libFuzzer: runs
 * LLVMFuzzerTestOneInput on every regular file of the directories (or on the files) named
 * on the command line, in name order, and ends with the plain line "N passed, M failed".
 * Each input runs in a child process, so an abort (a broken FUZZ_CHECK) or a crash is
 * reported with the file's name and the remaining inputs still run. Finding no input at
 * all is a failure too, so a mistyped corpus path cannot pass. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int passed, failed;

static void run_input(const char *path)
{
    FILE *f = fopen(path, "rb");
    uint8_t *buf;
    long size;
    if (!f || fseek(f, 0, SEEK_END) != 0 || (size = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fprintf(stderr, "replay: cannot read %s\n", path);
        exit(2);
    }
    /* Exactly `size` bytes, so a sanitizer build catches reads past the input. */
    buf = (uint8_t *)malloc(size ? (size_t)size : 1u);
    if (!buf || fread(buf, 1, (size_t)size, f) != (size_t)size) {
        fprintf(stderr, "replay: cannot read %s\n", path);
        exit(2);
    }
    fclose(f);
    LLVMFuzzerTestOneInput(buf, (size_t)size);
    free(buf);
}

static void run_file(const char *path)
{
    int status = 0;
    pid_t pid;
    fflush(NULL);
    pid = fork();
    if (pid == 0) {
        run_input(path);
        fflush(NULL);
        _exit(0);
    }
    if (pid < 0 || waitpid(pid, &status, 0) != pid) {
        fprintf(stderr, "replay: cannot run %s\n", path);
        failed++;
    } else if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        passed++;
    } else {
        if (WIFSIGNALED(status))
            fprintf(stderr, "replay: FAILED on %s (signal %d%s)\n", path, WTERMSIG(status),
                    WTERMSIG(status) == SIGABRT ? ", abort" : "");
        else
            fprintf(stderr, "replay: FAILED on %s (exit status %d)\n", path, WEXITSTATUS(status));
        failed++;
    }
}

int main(int argc, char **argv)
{
    int a;
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
            failed++;
        } else if (!S_ISDIR(st.st_mode)) {
            run_file(argv[a]);
        } else if ((n = scandir(argv[a], &list, NULL, alphasort)) < 0) {
            fprintf(stderr, "replay: cannot list %s\n", argv[a]);
            failed++;
        } else {
            for (i = 0; i < n; i++) {
                char path[4096];
                snprintf(path, sizeof path, "%s/%s", argv[a], list[i]->d_name);
                if (stat(path, &st) == 0 && S_ISREG(st.st_mode)) run_file(path);
                free(list[i]);
            }
            free(list);
        }
    }
    if (passed + failed == 0) {
        fprintf(stderr, "replay: no inputs found\n");
        failed++;
    }
    printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
