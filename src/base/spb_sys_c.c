/* spallbar: the system calls Fortran cannot make portably (struct stat's layout differs
 * between platforms). Used by src/base/spb_sys.f90 (sys_file_kind, sys_same_file). */
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

/* Whether two paths name the same existing file, following links: the same device and
 * inode (a hard link, a symbolic link or another spelling of the path). 0 when either is
 * missing. */
int spb_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    if (stat(a, &sa) != 0 || stat(b, &sb) != 0) return 0;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}
