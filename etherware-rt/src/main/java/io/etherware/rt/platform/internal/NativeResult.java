package io.etherware.rt.platform.internal;

/**
 * The outcome of one libc call: its return value and, when it failed, the {@code errno} captured
 * right after the call (before the JVM could overwrite it). Immutable.
 *
 * @param value the function's return value; negative means failure for every call we make
 * @param errno the captured errno when {@code value < 0}, else 0
 */
public record NativeResult(int value, int errno) {

    /** A result for a call that could not be made at all (not Linux, symbol missing). */
    public static final NativeResult UNAVAILABLE = new NativeResult(-1, Errno.ENOSYS);

    public boolean ok() {
        return value >= 0;
    }
}
