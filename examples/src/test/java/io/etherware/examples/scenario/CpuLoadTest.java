package io.etherware.examples.scenario;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

class CpuLoadTest {

    @Test
    void shouldAllocateWhileRunningAndStopItsThreadsWhenClosed() throws Exception {
        CpuLoad load = CpuLoad.start(1);
        long deadlineNs = System.nanoTime() + 10_000_000_000L;
        while (load.allocatedBytes() == 0 && System.nanoTime() < deadlineNs) {
            Thread.sleep(10);
        }
        load.close();
        long after = load.allocatedBytes();
        Thread.sleep(50);

        assertTrue(after > 0, "allocated something");
        assertEquals(after, load.allocatedBytes(), "nothing allocated after close");
        assertTrue(Thread.getAllStackTraces().keySet().stream().noneMatch(t -> t.getName().startsWith("cpu-load-")),
                "the load threads ended");
    }

    @Test
    void shouldRefuseANegativeThreadCount() {
        var e = assertThrows(IllegalArgumentException.class, () -> CpuLoad.start(-1));
        assertTrue(e.getMessage().contains("threadCount=-1"), e.getMessage());
    }
}
