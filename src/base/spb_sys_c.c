/* spallbar: the one system call Fortran cannot make portably (struct stat's layout differs
 * between platforms). Used by src/base/spb_sys.f90 (sys_file_kind). */
#include <sys/stat.h>

/* What path names, following links: -1 nothing (or not reachable), 0 a regular file,
 * 1 a folder, 2 anything else (a FIFO, a device, a socket). */
int spb_file_kind(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) return -1;
    if (S_ISREG(st.st_mode)) return 0;
    if (S_ISDIR(st.st_mode)) return 1;
    return 2;
}
