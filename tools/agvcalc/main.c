/*
 * agvcalc - the firmware's own algorithms on the host, as JSON Lines.
 *
 * One request object per input line on stdin, one response per line on stdout, in order
 * (agvcalc_answer(), agvcalc.c). The ops and their fields are listed by --help; their formats
 * are in docs/agvcalc.md.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "agvcalc.h"

int main(int argc, char **argv)
{
    if (argc > 1) {
        if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
            agvcalc_usage(stdout);
            return 0;
        }
        fprintf(stderr, "agvcalc: unknown argument %s\n", argv[1]);
        agvcalc_usage(stderr);
        return 2;
    }
    char *line = NULL;
    size_t cap = 0;
    ssize_t len;
    while ((len = getline(&line, &cap, stdin)) != -1) {
        while (len > 0 && (line[len - 1] == '\n' || line[len - 1] == '\r'))
            len--;
        char *s = agvcalc_answer(line, (size_t)len);
        puts(s ? s : "{\"ok\":false,\"error\":\"out of memory\"}");
        free(s);
        fflush(stdout);
    }
    free(line);
    return 0;
}
