package io.etherware.core.scheduler;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotSame;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Empty;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import java.util.ArrayList;
import java.util.Collections;
import java.util.IdentityHashMap;
import java.util.List;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/** The pool behind {@link Job#pooled} and {@link Job#recycle()}. */
class JobPoolTest {

    private static final Message MESSAGE = new Message(Profile.of("sink"), null, 0L, QoS.of(Criticality.HIGH),
            Empty.INSTANCE, new MessageId("test", 1), null);
    private static final Object TARGET = new Object();

    private static Job take(long sequence) {
        return Job.pooled(MESSAGE, "sink", TARGET, sequence, 7L);
    }

    /** Runs {@code body} on a new thread, so it starts with an empty pool of its own. */
    private static <T> T onFreshThread(java.util.concurrent.Callable<T> body) throws Exception {
        var result = new CompletableFuture<T>();
        Thread thread = Thread.ofPlatform().start(() -> {
            try {
                result.complete(body.call());
            } catch (Throwable e) {
                result.completeExceptionally(e);
            }
        });
        thread.join(TimeUnit.SECONDS.toMillis(30));
        return result.get(1, TimeUnit.SECONDS);
    }

    @Test
    void shouldReuseARecycledJobWithItsNewDeliveryAndNoPlacement() throws Exception {
        onFreshThread(() -> {
            Job first = take(1);
            first.place(2, 99);
            first.reserve();
            first.link(first);
            first.recycle();
            assertNull(first.message(), "a recycled job holds no message, so the pool pins none");

            var otherMessage = new Message(Profile.of("other"), null, 0L, QoS.of(Criticality.LOW), Empty.INSTANCE,
                    new MessageId("test", 2), null);
            Object otherTarget = new Object();
            Job second = Job.pooled(otherMessage, "other", otherTarget, 5, 11L);
            assertSame(first, second, "the recycled job is taken again");
            assertSame(otherMessage, second.message());
            assertEquals("other", second.targetName());
            assertSame(otherTarget, second.target());
            assertEquals(5, second.sequence());
            assertEquals(11L, second.releaseNs());
            assertFalse(second.isPlaced());
            assertFalse(second.isReserved());
            assertNull(second.link());
            return null;
        });
    }

    @Test
    void shouldReturnAJobRecycledOnAnotherThreadToThePoolOfTheThreadThatTookIt() throws Exception {
        onFreshThread(() -> {
            Job job = take(1);
            Thread recycler = Thread.ofPlatform().start(job::recycle);
            recycler.join();
            assertSame(job, take(2), "back in this thread's pool");
            assertNotSame(job, take(3), "and taken once");
            return null;
        });
    }

    @Test
    void shouldRefuseASecondRecycleAndKeepThePoolIntact() throws Exception {
        onFreshThread(() -> {
            Job job = take(1);
            job.recycle();
            IllegalStateException refused = assertThrows(IllegalStateException.class, job::recycle);
            assertTrue(refused.getMessage().contains("recycled twice"), refused.getMessage());
            assertSame(job, take(2));
            assertNotSame(job, take(3), "the job is in the pool once, not twice");
            return null;
        });
    }

    @Test
    void shouldGiveAVirtualThreadJobsOfNoPool() throws Exception {
        var taken = new CompletableFuture<Job[]>();
        Thread.ofVirtual().start(() -> {
            Job first = take(1);
            first.recycle();
            taken.complete(new Job[] {first, take(2)});
        });
        Job[] jobs = taken.get(10, TimeUnit.SECONDS);
        assertNotSame(jobs[0], jobs[1], "no pool: nothing is reused");
        assertSame(MESSAGE, jobs[0].message(), "and recycling leaves the job as it is");
    }

    @Test
    void shouldLeaveAJobMadeWithTheConstructorAsItIs() {
        var job = new Job(MESSAGE, "sink", TARGET, 1, 0L);
        job.recycle();
        job.recycle();
        assertSame(MESSAGE, job.message(), "not pooled: recycling it changes nothing");
    }

    @Test
    void shouldKeepAtMostItsCapacityOfABurstSoTheBurstDoesNotPinMemory() throws Exception {
        onFreshThread(() -> {
            var burst = new ArrayList<Job>();
            for (int i = 0; i < JobPool.CAPACITY + 10; i++) {
                burst.add(take(i));
            }
            burst.forEach(Job::recycle);
            Set<Job> kept = Collections.newSetFromMap(new IdentityHashMap<>());
            kept.addAll(burst.subList(0, JobPool.CAPACITY));
            Set<Job> again = Collections.newSetFromMap(new IdentityHashMap<>());
            for (int i = 0; i < JobPool.CAPACITY; i++) {
                again.add(take(i));
            }
            assertEquals(kept, again, "the first CAPACITY recycled came back, each once");
            Job beyond = take(0);
            assertTrue(burst.stream().noneMatch(job -> job == beyond), "the burst's extra jobs were not kept");
            return null;
        });
    }

    @Test
    void shouldReuseJobsAgainAfterManyWereNeverRecycled() throws Exception {
        onFreshThread(() -> {
            for (int i = 0; i < 3 * JobPool.CAPACITY; i++) {
                take(i); // discarded, forwarded elsewhere, or run by a scheduler that does not recycle
            }
            Job job = take(1);
            job.recycle();
            assertSame(job, take(2), "jobs that never came back do not use the pool up");
            return null;
        });
    }

    @Test
    void shouldGiveAJobBackOnceWhenTwoThreadsRecycleItAtOnce() throws Exception {
        onFreshThread(() -> {
            for (int round = 0; round < 200; round++) {
                Job job = take(round);
                var start = new java.util.concurrent.CountDownLatch(1);
                var refused = new java.util.concurrent.atomic.AtomicInteger();
                Runnable recycle = () -> {
                    try {
                        start.await();
                        job.recycle();
                    } catch (IllegalStateException e) {
                        refused.incrementAndGet();
                    } catch (InterruptedException e) {
                        Thread.currentThread().interrupt();
                    }
                };
                Thread first = Thread.ofPlatform().start(recycle);
                Thread second = Thread.ofPlatform().start(recycle);
                start.countDown();
                first.join();
                second.join();
                assertEquals(1, refused.get(), "round " + round + ": exactly one of the two recycles is refused");
                assertSame(job, take(0));
                assertNotSame(job, take(1), "round " + round + ": the job is in the pool once");
            }
            return null;
        });
    }

    @Test
    void shouldHandEveryJobBackExactlyOnceWhenManyThreadsRecycleAtOnce() throws Exception {
        ExecutorService recyclers = Executors.newFixedThreadPool(4);
        try {
            onFreshThread(() -> {
                Set<Job> owned = Collections.newSetFromMap(new IdentityHashMap<>());
                for (int round = 0; round < 200; round++) {
                    var jobs = new ArrayList<Job>();
                    for (int i = 0; i < 256; i++) {
                        jobs.add(take(i));
                    }
                    Set<Job> distinct = Collections.newSetFromMap(new IdentityHashMap<>());
                    distinct.addAll(jobs);
                    assertEquals(jobs.size(), distinct.size(), "round " + round + ": a job was handed out twice");
                    owned.addAll(jobs);
                    List<Future<?>> done = new ArrayList<>();
                    for (int part = 0; part < 4; part++) {
                        List<Job> slice = jobs.subList(part * 64, (part + 1) * 64);
                        done.add(recyclers.submit(() -> slice.forEach(Job::recycle)));
                    }
                    for (Future<?> future : done) {
                        future.get(10, TimeUnit.SECONDS);
                    }
                }
                assertEquals(256, owned.size(), "every round reused the same 256 jobs: none lost, none made anew");
                return null;
            });
        } finally {
            recyclers.shutdownNow();
        }
    }
}
