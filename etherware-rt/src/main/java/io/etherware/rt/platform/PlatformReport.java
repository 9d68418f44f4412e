package io.etherware.rt.platform;

import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.Optional;

/**
 * What a scheduler's threads asked of the OS and got: one line per dispatcher, requested vs
 * granted, plus the memory lock, the CPU latency request and the CPU partition when they were
 * requested. A node logs it at start. Immutable.
 *
 * @param threads             one grant per dispatcher thread, in dispatcher order
 * @param memoryLockRequested whether {@code mlockall} was requested
 * @param memoryLockRefusal   why the memory lock was refused; empty when granted or not requested
 * @param processLines        one line each for the process-wide requests (CPU latency, partition)
 *                            that were made; empty when none was
 * @param processRefusals     what of those was refused; empty when everything was granted
 */
public record PlatformReport(List<ThreadGrant> threads, boolean memoryLockRequested,
                             Optional<PlatformRefusal> memoryLockRefusal, List<String> processLines,
                             List<PlatformRefusal> processRefusals) {

    /**
     * Keeps unmodifiable copies of the lists.
     *
     * @throws NullPointerException when a list or {@code memoryLockRefusal} is null, or a list
     *                              holds a null
     */
    public PlatformReport {
        threads = List.copyOf(threads);
        Objects.requireNonNull(memoryLockRefusal, "memoryLockRefusal");
        processLines = List.copyOf(processLines);
        processRefusals = List.copyOf(processRefusals);
    }

    /**
     * A report of thread grants and the memory lock only, with no process-wide lines.
     *
     * @param threads             one grant per dispatcher thread, in dispatcher order
     * @param memoryLockRequested whether {@code mlockall} was requested
     * @param memoryLockRefusal   why the memory lock was refused; empty when granted or not requested
     */
    public PlatformReport(List<ThreadGrant> threads, boolean memoryLockRequested,
                          Optional<PlatformRefusal> memoryLockRefusal) {
        this(threads, memoryLockRequested, memoryLockRefusal, List.of(), List.of());
    }

    /**
     * Whether the OS granted everything asked of it.
     *
     * @return true when no thread, no memory lock and no process-wide request was refused
     */
    public boolean isFullyGranted() {
        return threads.stream().allMatch(grant -> grant.refusals().isEmpty()) && memoryLockRefusal.isEmpty()
                && processRefusals.isEmpty();
    }

    /**
     * The report as text lines, for a node's start-up log.
     *
     * @return one line per dispatcher, then the memory lock, CPU latency and partition lines when
     *         they were requested; a new list the caller owns
     */
    public List<String> lines() {
        var lines = new ArrayList<String>();
        threads.forEach(grant -> lines.add(grant.toLine()));
        if (memoryLockRequested) {
            lines.add("memory: requested mlockall(MCL_CURRENT|MCL_FUTURE), "
                    + memoryLockRefusal.map(refusal -> "refused [" + refusal + "]").orElse("granted"));
        }
        lines.addAll(processLines);
        return lines;
    }

    /** {@link #lines()}, joined with the platform's line separator. */
    @Override
    public String toString() {
        return String.join(System.lineSeparator(), lines());
    }
}
