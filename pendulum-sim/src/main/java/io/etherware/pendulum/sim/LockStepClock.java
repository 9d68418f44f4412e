package io.etherware.pendulum.sim;

import io.etherware.core.time.NodeClock;
import java.util.ArrayList;
import java.util.List;
import java.util.function.BooleanSupplier;

/**
 * Simulated time for deterministic lock-step runs: the DSP board, the simulated serial link and
 * the test's controller all read this clock, and time moves only when someone waits.
 *
 * <p>Time advances from event to event: each {@link Participant} says when its next event is
 * (the board's next plant step, the link's next byte arrival), the clock jumps to the earliest
 * and lets every participant catch up to it. A controller that waits for a reply or for its next
 * period calls {@link #advanceUntil} or {@link #advanceTo}, which run the world until then. A run
 * is therefore a pure function of its inputs and seeds.
 *
 * <p>Confined to one thread: register, advance and read on the thread that drives the run.
 * {@link #nanoTime()} may be read from other threads (it is volatile) but does not move on its own.
 */
public final class LockStepClock implements NodeClock {

    /** Something that lives in simulated time. */
    public interface Participant {
        /**
         * When this participant's next event is. Must not wait or change state.
         *
         * @param nowNs the clock's current simulated time, in nanoseconds
         * @return the time of the next event strictly after {@code nowNs}, in nanoseconds, or
         *     {@link Long#MAX_VALUE} when none is pending
         */
        long nextEventNs(long nowNs);

        /**
         * Catches up to {@code nowNs}, handling every event due at or before it. Must not wait:
         * no blocking reads, no calls back into {@link #advanceTo} or {@link #advanceUntil}.
         *
         * @param nowNs the new simulated time, in nanoseconds
         */
        void advanceTo(long nowNs);
    }

    private static final long EPOCH_AT_ZERO_NS = 1_767_225_600_000_000_000L; // 2026-01-01T00:00Z

    private final List<Participant> participants = new ArrayList<>();
    private volatile long nowNs;

    /** A clock at time 0. */
    public LockStepClock() {}

    /**
     * Adds a participant; it is first advanced at the next move of time.
     *
     * @param participant the participant, on the thread that drives the run
     */
    public void register(Participant participant) {
        participants.add(participant);
    }

    /**
     * The simulated time; readable from any thread, it moves only in {@link #advanceUntil}.
     *
     * @return nanoseconds since the clock was made
     */
    @Override
    public long nanoTime() {
        return nowNs;
    }

    /**
     * The simulated time as a wall-clock time, starting at 2026-01-01T00:00Z.
     *
     * @return nanoseconds since the Unix epoch
     */
    @Override
    public long epochNanos() {
        return EPOCH_AT_ZERO_NS + nowNs;
    }

    /**
     * Runs the world up to a time (no-op if it is in the past).
     *
     * @param targetNs the simulated time to reach, in nanoseconds
     */
    public void advanceTo(long targetNs) {
        advanceUntil(() -> false, targetNs);
    }

    /**
     * Runs the world event by event until {@code ready} holds or time reaches {@code deadlineNs}.
     *
     * @param ready      checked before each move of time, on this thread
     * @param deadlineNs the simulated time at which to give up, in nanoseconds
     * @return whether {@code ready} held
     */
    public boolean advanceUntil(BooleanSupplier ready, long deadlineNs) {
        while (!ready.getAsBoolean()) {
            long now = nowNs;
            if (now >= deadlineNs) {
                return false;
            }
            long next = deadlineNs;
            for (Participant participant : participants) {
                next = Math.min(next, participant.nextEventNs(now));
            }
            // A participant must report events strictly after now; never stall time.
            next = Math.max(next, now + 1);
            nowNs = next;
            for (Participant participant : participants) {
                participant.advanceTo(next);
            }
        }
        return true;
    }
}
