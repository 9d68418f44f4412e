package io.etherware.core.scheduler;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.time.NodeClock;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.stream.LongStream;
import org.junit.jupiter.api.Test;

class FifoSchedulerTest {

    private static Job job(long sequence) {
        var message = new Message(Profile.of("x"), null, 0, QoS.NONE, new Text("j" + sequence),
                new MessageId("test", sequence), null);
        return new Job(message, "x", new Object(), sequence, 0);
    }

    @Test
    void shouldRunJobsOneByOneInSubmissionOrderOnOneThread() throws Exception {
        var scheduler = new FifoScheduler("fifo-test");
        var order = new CopyOnWriteArrayList<Long>();
        var threads = new CopyOnWriteArrayList<String>();
        var done = new CountDownLatch(1000);
        scheduler.start((job, nowNs) -> {
            order.add(job.sequence());
            threads.add(Thread.currentThread().getName());
            done.countDown();
            return true;
        }, NodeClock.system());
        for (long i = 0; i < 1000; i++) {
            assertTrue(scheduler.submit(job(i)));
        }
        assertTrue(done.await(30, TimeUnit.SECONDS));
        assertEquals(LongStream.range(0, 1000).boxed().toList(), order);
        assertEquals(1, threads.stream().distinct().count());
        assertEquals("fifo-test", threads.getFirst());
        assertEquals(List.of(), scheduler.shutdown(TimeUnit.SECONDS.toNanos(1)));
    }

    @Test
    void shouldReturnTheUnrunJobsAndRefuseNewOnesWhenShutDown() throws Exception {
        var scheduler = new FifoScheduler();
        var entered = new CountDownLatch(1);
        var release = new CountDownLatch(1);
        var ran = new AtomicInteger();
        scheduler.start((job, nowNs) -> {
            ran.incrementAndGet();
            entered.countDown();
            try {
                release.await(30, TimeUnit.SECONDS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
            return true;
        }, NodeClock.system());
        for (long i = 0; i < 10; i++) {
            scheduler.submit(job(i));
        }
        assertTrue(entered.await(30, TimeUnit.SECONDS));
        Thread releaser = Thread.ofPlatform().start(() -> {
            try {
                Thread.sleep(200); // after the 10 ms drain gave up
            } catch (InterruptedException e) {
                return;
            }
            release.countDown();
        });
        List<Job> unrun = scheduler.shutdown(TimeUnit.MILLISECONDS.toNanos(10));
        releaser.join();
        // The first job held the dispatcher well past the drain timeout: the rest are returned.
        assertEquals(10, ran.get() + unrun.size(), "every job ran or was returned");
        assertTrue(unrun.size() >= 1, "the drain gave up after 10 ms, long before the 200 ms release");
        assertEquals(10 - unrun.size(), unrun.getFirst().sequence(), "the returned jobs are the last ones, in order");
        assertFalse(scheduler.submit(job(99)));
        assertEquals(0, unrun.getFirst().dispatcherId());
    }

    @Test
    void shouldKeepTheDispatcherAliveWhenTheRunnerThrows() throws Exception {
        var scheduler = new FifoScheduler();
        var ran = new CountDownLatch(2);
        scheduler.start((job, nowNs) -> {
            ran.countDown();
            if (job.sequence() == 0) {
                throw new IllegalStateException("kernel bug");
            }
            return true;
        }, NodeClock.system());
        scheduler.submit(job(0));
        scheduler.submit(job(1));
        assertTrue(ran.await(30, TimeUnit.SECONDS));
        scheduler.shutdown(TimeUnit.SECONDS.toNanos(1));
    }
}
