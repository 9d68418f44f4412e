package io.etherware.rt.platform;

import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.Optional;

/**
 * What a scheduler's threads asked of the OS and got: one line per dispatcher, requested vs
 * granted, plus the memory lock when one was requested. A node logs it at start. Immutable.
 *
 * @param threads             one grant per dispatcher thread, in dispatcher order
 * @param memoryLockRequested whether {@code mlockall} was requested
 * @param memoryLockRefusal   why the memory lock was refused; empty when granted or not requested
 */
public record PlatformReport(List<ThreadGrant> threads, boolean memoryLockRequested,
                             Optional<PlatformRefusal> memoryLockRefusal) {

    public PlatformReport {
        threads = List.copyOf(threads);
        Objects.requireNonNull(memoryLockRefusal, "memoryLockRefusal");
    }

    /** Whether every thread got the policy it asked for, and memory was locked if asked. */
    public boolean isFullyGranted() {
        return threads.stream().allMatch(grant -> grant.refusals().isEmpty()) && memoryLockRefusal.isEmpty();
    }

    /** One line per dispatcher, then one for the memory lock when it was requested. */
    public List<String> lines() {
        var lines = new ArrayList<String>();
        threads.forEach(grant -> lines.add(grant.toLine()));
        if (memoryLockRequested) {
            lines.add("memory: requested mlockall(MCL_CURRENT|MCL_FUTURE), "
                    + memoryLockRefusal.map(refusal -> "refused [" + refusal + "]").orElse("granted"));
        }
        return lines;
    }

    @Override
    public String toString() {
        return String.join(System.lineSeparator(), lines());
    }
}
