package io.etherware.rt.platform.internal;

import io.etherware.rt.platform.PlatformRefusal;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.AtomicLong;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Logs each kind of platform refusal once per JVM (design decision 6: real priorities or a loud
 * warning, never a silent fallback, but not one warning per thread either). The kind is the
 * feature plus the errno, so three dispatchers refused SCHED_FIFO with EPERM give one warning;
 * each still appears in the {@code PlatformReport}.
 *
 * <p>Thread-safe.
 */
public final class RefusalWarnings {

    private static final Logger LOG = LoggerFactory.getLogger("io.etherware.rt.platform");
    private static final RefusalWarnings SHARED = new RefusalWarnings();

    private final Set<String> warned = ConcurrentHashMap.newKeySet();
    private final AtomicLong warnings = new AtomicLong();

    /** The JVM-wide instance. */
    public static RefusalWarnings shared() {
        return SHARED;
    }

    /** Logs {@code refusal} at WARN unless one of its kind was already logged. */
    public void warnOnce(PlatformRefusal refusal) {
        if (warned.add(refusal.feature() + "/" + refusal.errno())) {
            warnings.incrementAndGet();
            LOG.warn("{} {} refused: {}; running on without it. Fix: {}", refusal.feature(), refusal.requested(),
                    Errno.describe(refusal.errno()), refusal.fix());
        }
    }

    /** How many warnings this instance has logged. */
    public long warningsLogged() {
        return warnings.get();
    }
}
