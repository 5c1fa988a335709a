/* The thin C layer of the case locks (module visco2d_system, bind(c)): an
 * flock(2) on a lock file OUT/.<case>.lock, held for the life of the run of
 * that case. The kernel (or the file server, for NFS and the cluster file
 * systems that support flock) drops the lock when the holder ends in any way,
 * so a held lock means a live run, on this host or another, in this PID
 * namespace or another. The file holds "<host> <pid>" of its holder, for the
 * messages. Every function returns what its comment says; none exits. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

/* Copy what the lock file of fd holds (at most size-1 bytes, up to a line
 * break) into holder, null-terminated. */
static void read_holder(int fd, char *holder, int size) {
    ssize_t got;
    if (size < 1) return;
    got = pread(fd, holder, (size_t)(size - 1), 0);
    if (got < 0) got = 0;
    holder[got] = '\0';
    holder[strcspn(holder, "\r\n")] = '\0';
}

/* Take the lock of path without waiting: the open file descriptor (>= 0)
 * when this process now holds it (holder: what the file held before; the
 * file then holds `text`, unless text is ""); -1 if another
 * process holds it (holder: what the file says of it); -2 if the file cannot
 * be created or locked (holder: strerror). A lock file removed by its
 * releaser between the open and the flock is opened again; if `patient`, a
 * lock held for less than 0.2 s (another run's check for stale folders) is waited for. */
int visco2d_lock_take(const char *path, const char *text, char *holder, int size, int patient) {
    int attempt, busy = 0;
    if (size > 0) holder[0] = '\0';
    for (attempt = 0; attempt < 1000; attempt++) {
        struct stat opened, named;
        int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd < 0) {
            if (size > 0) { strncpy(holder, strerror(errno), (size_t)size - 1); holder[size - 1] = '\0'; }
            return -2;
        }
        if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
            int reason = errno;
            if (reason == EWOULDBLOCK || reason == EAGAIN) {
                read_holder(fd, holder, size);
                close(fd);
                /* A run's lock lasts as long as the run; a check for stale folders
                 * holds one for microseconds: ask again for 0.2 s before giving up. */
                if (!patient || ++busy > 20) return -1;
                usleep(10000);
                continue;
            }
            if (size > 0) { strncpy(holder, strerror(reason), (size_t)size - 1); holder[size - 1] = '\0'; }
            close(fd);
            return -2;
        }
        if (fstat(fd, &opened) == 0 && stat(path, &named) == 0 && opened.st_dev == named.st_dev &&
            opened.st_ino == named.st_ino) {
            size_t length = strlen(text);
            read_holder(fd, holder, size);
            if (length > 0 && (ftruncate(fd, 0) != 0 || pwrite(fd, text, length, 0) != (ssize_t)length)) {
                /* the holder's name is for messages only: the lock is held all the same */
            }
            return fd;
        }
        close(fd);   /* that file was removed (released) meanwhile: lock the one now at path */
    }
    if (size > 0) { strncpy(holder, "the lock file keeps changing", (size_t)size - 1); holder[size - 1] = '\0'; }
    return -2;
}

/* Release a lock taken by visco2d_lock_take: remove the file (while still
 * holding it), then close it. */
void visco2d_lock_release(int fd, const char *path) {
    if (fd < 0) return;
    unlink(path);
    close(fd);
}

/* Close a lock file without removing it (a check of a lock another host's run may still name). */
void visco2d_lock_close(int fd) {
    if (fd >= 0) close(fd);
}

/* Hold (hold != 0) or let through again (hold == 0) SIGINT and SIGTERM:
 * while a lock is taken and armed for removal on an interrupt, or disarmed
 * and released, an interrupt waits, so that it never ends the process
 * between the two and leaves the lock file behind. Returns 0, or -1 when
 * the signal mask cannot be changed. */
int visco2d_hold_interrupts(int hold) {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    return sigprocmask(hold ? SIG_BLOCK : SIG_UNBLOCK, &set, NULL) == 0 ? 0 : -1;
}

/* The host name (gethostname), null-terminated; "" if unknown. */
void visco2d_host_name(char *name, int size) {
    if (size < 1) return;
    if (gethostname(name, (size_t)size - 1) != 0) name[0] = '\0';
    name[size - 1] = '\0';
}
