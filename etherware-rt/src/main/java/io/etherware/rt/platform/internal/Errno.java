package io.etherware.rt.platform.internal;

import java.util.Map;

/**
 * Linux errno numbers we meet in scheduling calls, with their symbolic names, so a warning says
 * {@code EPERM (errno 1)} rather than a bare number. Values are the Linux generic ones (x86-64,
 * aarch64). Stateless and thread-safe.
 */
public final class Errno {
    public static final int EPERM = 1;
    public static final int ENOENT = 2;
    public static final int ESRCH = 3;
    public static final int EINTR = 4;
    public static final int EIO = 5;
    public static final int EAGAIN = 11;
    public static final int ENOMEM = 12;
    public static final int EACCES = 13;
    public static final int EFAULT = 14;
    public static final int EINVAL = 22;
    public static final int ENOSYS = 38;

    private static final Map<Integer, String[]> NAMES = Map.ofEntries(
            Map.entry(EPERM, new String[] {"EPERM", "Operation not permitted"}),
            Map.entry(ENOENT, new String[] {"ENOENT", "No such file or directory"}),
            Map.entry(ESRCH, new String[] {"ESRCH", "No such process"}),
            Map.entry(EINTR, new String[] {"EINTR", "Interrupted system call"}),
            Map.entry(EIO, new String[] {"EIO", "Input/output error"}),
            Map.entry(EAGAIN, new String[] {"EAGAIN", "Resource temporarily unavailable"}),
            Map.entry(ENOMEM, new String[] {"ENOMEM", "Cannot allocate memory"}),
            Map.entry(EACCES, new String[] {"EACCES", "Permission denied"}),
            Map.entry(EFAULT, new String[] {"EFAULT", "Bad address"}),
            Map.entry(16, new String[] {"EBUSY", "Device or resource busy"}),
            Map.entry(EINVAL, new String[] {"EINVAL", "Invalid argument"}),
            Map.entry(ENOSYS, new String[] {"ENOSYS", "Function not implemented"}),
            Map.entry(95, new String[] {"EOPNOTSUPP", "Operation not supported"}));

    private Errno() {
    }

    /** The symbolic name, e.g. {@code EPERM}, or {@code errno N} for one we do not know. */
    public static String name(int errno) {
        String[] entry = NAMES.get(errno);
        return entry != null ? entry[0] : "errno " + errno;
    }

    /** The usual strerror text, or an empty string for one we do not know. */
    public static String description(int errno) {
        String[] entry = NAMES.get(errno);
        return entry != null ? entry[1] : "";
    }

    /** {@code EPERM (errno 1: Operation not permitted)}. */
    public static String describe(int errno) {
        String text = description(errno);
        return name(errno) + " (errno " + errno + (text.isEmpty() ? "" : ": " + text) + ")";
    }
}
