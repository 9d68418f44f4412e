package io.etherware.services.network.internal;

import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

class GenerationsTest {

    @Test
    void shouldHoldABarrierUntilEveryEarlierMessageIsSettledInWhateverOrder() {
        var generations = new Generations();
        long first = generations.take();
        long second = generations.take();
        long barrier = generations.close();
        long later = generations.take(); // e.g. a HIGH message queued after the barrier, written first
        generations.settle(later);
        assertFalse(generations.settledUpTo(barrier), "a later message settled first does not count");
        generations.settle(second);
        assertFalse(generations.settledUpTo(barrier), "one earlier message is still unsettled");
        generations.settle(first);
        assertTrue(generations.settledUpTo(barrier));
    }

    @Test
    void shouldPassABarrierAtOnceWhenNothingIsUnsettled() {
        var generations = new Generations();
        generations.settle(generations.take());
        assertTrue(generations.settledUpTo(generations.close()));
        long pending = generations.take();
        long next = generations.close();
        assertFalse(generations.settledUpTo(next));
        generations.settle(pending);
        assertTrue(generations.settledUpTo(next));
    }

    @Test
    void shouldKeepBarriersInOrder() {
        var generations = new Generations();
        long a = generations.take();
        long firstBarrier = generations.close();
        long b = generations.take();
        long secondBarrier = generations.close();
        generations.settle(a);
        assertTrue(generations.settledUpTo(firstBarrier));
        assertFalse(generations.settledUpTo(secondBarrier));
        generations.settle(b);
        assertTrue(generations.settledUpTo(secondBarrier));
    }
}
