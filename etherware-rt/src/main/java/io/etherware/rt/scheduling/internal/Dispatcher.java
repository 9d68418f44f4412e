package io.etherware.rt.scheduling.internal;

import io.etherware.core.scheduler.Job;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.PlatformRefusal;
import io.etherware.rt.platform.ThreadGrant;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.platform.internal.Errno;
import io.etherware.rt.platform.internal.LinuxNative;
import io.etherware.rt.scheduling.DeadlineMiss;
import io.etherware.rt.scheduling.DispatcherSpec;
import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.util.ArrayList;
import java.util.Collection;
import java.util.List;
import java.util.PriorityQueue;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.LockSupport;
import java.util.concurrent.locks.ReentrantLock;
import jdk.jfr.EventType;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * One dispatcher of the Dispatching Module (paper Fig. 4): a platform thread at a fixed OS
 * priority with its own priority queue, ordered by placement key, ties by arrival sequence.
 *
 * <p>Hand-off: submitters push onto a lock-free intake and unpark the thread only if it is
 * parked; the thread takes the whole intake into its private heap before every take. No submitter
 * ever holds a lock the dispatcher needs, so a low-priority submitter preempted mid-submit cannot
 * delay a high-priority dispatcher (no lock-holder preemption on the hand-off path). The intake is
 * a Treiber stack chained through the jobs themselves ({@link Job#link}): a push is one CAS and
 * allocates nothing, and a job is visible whole or not at all, so a preempted pusher never holds
 * back jobs pushed after it. Taking the whole stack at once (one swap) avoids the ABA problem of
 * popping single nodes. Its order does not matter: the heap orders by key, then arrival sequence.
 * A job that ran is handed back for reuse ({@link Job#recycle()}) once this thread is done with
 * it. Measured with
 * the dispatch-latency harness (now section 2 of {@code etherware-demo bench}) on a loaded 2-vCPU
 * VM against a PriorityBlockingQueue per dispatcher: the same p99 (about 25 µs) under the LOW flood, but a p99.9 of 0.1-0.5 ms instead
 * of 0.2-18 ms.
 *
 * <p>Priority inheritance: when a job taken here is parked because its component is running on a
 * lower-priority dispatcher, that dispatcher's thread is raised to this one's priority until its
 * current job ends, so a HIGH job waits for at most the remainder of that one job, not for the
 * middle-priority work that would otherwise preempt it.
 *
 * <p>Threading: {@link #offer} from any thread; everything else on the dispatcher thread, except
 * {@link #inheritPriority} (from another dispatcher's thread, serialized by a lock) and the
 * shutdown methods, documented as such.
 */
public final class Dispatcher implements Runnable {

    private static final Logger LOG = LoggerFactory.getLogger(Dispatcher.class);
    private static final VarHandle INTAKE;
    /** The dispatch event's type, or null on a JVM built without the Flight Recorder. */
    private static final EventType DISPATCH_EVENTS = dispatchEventType();

    static {
        try {
            INTAKE = MethodHandles.lookup().findVarHandle(Dispatcher.class, "intake", Job.class);
        } catch (ReflectiveOperationException e) {
            throw new ExceptionInInitializerError(e);
        }
    }

    private final int id;
    private final DispatcherSpec spec;
    private final DispatchContext context;
    private final DispatcherRecorder recorder;
    private final Thread thread;
    /** The intake's top, a stack chained through {@link Job#link}; pushed by any thread, taken whole here. */
    @SuppressWarnings("unused") // through INTAKE
    private volatile Job intake;
    private final PriorityQueue<Job> ready = new PriorityQueue<>(64, Keys.BY_KEY_THEN_SEQUENCE);
    private final CountDownLatch started = new CountDownLatch(1);
    private final ReentrantLock boostLock = new ReentrantLock();
    private volatile boolean waiting;
    private volatile ThreadGrant grant;
    private volatile Object runningTarget;
    /** The priority lent to this thread by a waiting job, 0 when none. Written under boostLock. */
    private volatile int boostedPriority;
    private boolean failureLogged;

    public Dispatcher(int id, DispatcherSpec spec, DispatchContext context, DispatcherRecorder recorder,
                      String threadName) {
        this.id = id;
        this.spec = spec;
        this.context = context;
        this.recorder = recorder;
        // Daemon: the application (or the node) decides when the JVM ends, and a component stuck
        // past shutdown must not keep it alive.
        this.thread = Thread.ofPlatform().name(threadName).daemon(true).unstarted(this);
    }

    public void start() {
        thread.start();
    }

    /** Waits until the thread has configured itself; returns what the OS granted, or null on timeout. */
    public ThreadGrant awaitGrant(long timeoutNs) throws InterruptedException {
        return started.await(timeoutNs, TimeUnit.NANOSECONDS) ? grant : null;
    }

    /** Any thread: queues a placed job. False when the scheduler no longer takes it. */
    public boolean offer(Job job) {
        context.submitted.incrementAndGet();
        int state = context.state;
        if (state != DispatchContext.RUNNING && !(state == DispatchContext.DRAINING && job.isReserved())) {
            context.finished.incrementAndGet();
            return false;
        }
        Job top;
        do {
            top = intake;
            job.link(top);
        } while (!INTAKE.compareAndSet(this, top, job));
        recorder.recordEnqueued();
        // The intake's CAS orders this read after the push; the dispatcher sets waiting before
        // its last look at the intake, so either it sees the job or we see it waiting.
        if (waiting) {
            LockSupport.unpark(thread);
        }
        return true;
    }

    @Override
    public void run() {
        try {
            // First-time class loading and initialization (the JFR events) at the inherited,
            // ordinary priority, before the real-time one: at SCHED_FIFO it would hold a CPU
            // against the JVM's own ordinary threads (JIT compilers, the VM thread), which the
            // other dispatchers starting beside it may be waiting for.
            preloadPerJobClasses();
            // The scheduler warns for all dispatchers at once, once it has every grant.
            grant = Platform.current().configureCurrentThreadWithoutWarning(spec.policy(), spec.cpus());
        } catch (RuntimeException e) {
            LOG.error("dispatcher {} could not prepare or configure its thread; it runs at the inherited priority",
                    thread.getName(), e);
            grant = new ThreadGrant(thread.getName(), -1, spec.policy(), ThreadPolicy.NON_REALTIME, spec.cpus(),
                    CpuSet.inherit(), List.of(new PlatformRefusal("thread priority", spec.policy().toString(),
                            Errno.ENOSYS, Errno.name(Errno.ENOSYS), e.toString())));
        } finally {
            started.countDown();
        }
        for (Job job = next(); job != null; job = next()) {
            execute(job);
        }
    }

    /**
     * Loads and initializes the JFR event classes the per-job path uses, on this thread before it
     * reports started, so the first message does not pay for their class loading.
     */
    private static void preloadPerJobClasses() {
        new DispatchEvent().shouldCommit();
        new DeadlineMissEvent().shouldCommit();
    }

    /** The next job by key then sequence, parking while there is none; null once aborted. */
    private Job next() {
        while (true) {
            moveIntakeTo(ready);
            if (context.state == DispatchContext.ABORTED) {
                return null;
            }
            Job job = ready.poll();
            if (job != null) {
                recorder.recordDequeued();
                return job;
            }
            waiting = true;
            if (intake == null && context.state != DispatchContext.ABORTED) {
                LockSupport.park(this);
                // An interrupt left behind by a component would make every later park return at
                // once: clear it so waiting stays waiting, not spinning.
                Thread.interrupted();
            }
            waiting = false;
        }
    }

    private static EventType dispatchEventType() {
        try {
            return EventType.getEventType(DispatchEvent.class);
        } catch (InternalError | RuntimeException e) {
            return null; // "Flight Recorder is not supported on this VM": no events, the dispatcher runs on
        }
    }

    /** Takes the whole intake (one swap) into {@code jobs}, unlinked: the heap, or the jobs drained at shutdown. */
    private void moveIntakeTo(Collection<Job> jobs) {
        Job job = intake == null ? null : (Job) INTAKE.getAndSet(this, (Job) null);
        while (job != null) {
            Job next = job.link();
            job.link(null);
            jobs.add(job);
            job = next;
        }
    }

    private void execute(Job job) {
        long startNs = context.clock.nanoTime();
        // Made only while a recording takes the event: not left to escape analysis, which does not
        // remove it until the method is compiled again after a deoptimization.
        DispatchEvent event = DISPATCH_EVENTS != null && DISPATCH_EVENTS.isEnabled() ? new DispatchEvent() : null;
        if (event != null) {
            event.begin();
        }
        runningTarget = job.target();
        boolean ran = true;
        boolean returned = false;
        try {
            ran = context.runner.run(job, startNs);
            returned = true;
        } catch (Throwable failure) {
            recordFailure("the kernel's runner", job, failure);
        } finally {
            runningTarget = null;
            if (boostedPriority != 0) {
                endBoost();
            }
        }
        long endNs = context.clock.nanoTime();
        if (ran) {
            account(job, startNs, endNs);
        } else {
            if (context.priorityInheritance) {
                lendPriorityFor(job);
            }
            // Counted after the loan, so whoever sees the count also sees the holder's boost.
            recorder.recordParked();
        }
        context.finished.incrementAndGet();
        if (event != null) {
            commit(event, job, startNs, ran);
        }
        if (ran && returned) {
            // It ran and nothing refers to it any more. Not after a throw from the kernel: where
            // the job ended up then is unknown, so it is left to the garbage collector.
            job.recycle();
        }
    }

    private void commit(DispatchEvent event, Job job, long startNs, boolean ran) {
        event.end();
        if (event.shouldCommit()) {
            event.dispatcher = id;
            event.component = job.targetName();
            event.message = job.message().messageId().toString();
            event.criticality = job.message().qos().criticality().name();
            event.key = job.key();
            event.startLatency = startNs - job.releaseNs();
            event.ran = ran;
            event.commit();
        }
    }

    private void account(Job job, long startNs, long endNs) {
        long executionNs = endNs - startNs;
        long deadlineNs = job.absoluteDeadlineNs();
        boolean missed = deadlineNs != Long.MAX_VALUE && endNs > deadlineNs;
        ComponentRecorder component = context.components.get(job.targetName());
        if (component == null) {
            component = context.components.computeIfAbsent(job.targetName(), name -> new ComponentRecorder());
        }
        component.recordRun(executionNs, missed);
        if (missed) {
            onMiss(job, startNs, endNs, deadlineNs);
        }
        // Last, so that a reader who sees the dispatcher's run count sees the job's other figures too.
        recorder.recordRun(startNs - job.releaseNs(), executionNs);
    }

    private void onMiss(Job job, long startNs, long endNs, long deadlineNs) {
        recorder.recordMiss();
        var miss = new DeadlineMiss(id, job.targetName(), job.message().messageId(), job.message().qos().criticality(),
                job.releaseNs(), startNs, endNs, deadlineNs);
        try {
            context.missHandler.onDeadlineMiss(miss);
        } catch (Throwable failure) {
            recordFailure("the deadline miss handler", job, failure);
        }
        var event = new DeadlineMissEvent();
        if (event.shouldCommit()) {
            event.dispatcher = id;
            event.component = miss.component();
            event.message = miss.messageId().toString();
            event.criticality = miss.criticality().name();
            event.lateness = miss.latenessNs();
            event.startLatency = startNs - job.releaseNs();
            event.executionTime = endNs - startNs;
            event.commit();
        }
    }

    private void recordFailure(String what, Job job, Throwable failure) {
        recorder.recordFailure();
        if (!failureLogged) {
            failureLogged = true;
            LOG.error("dispatcher {}: {} threw for {}; the dispatcher runs on (further failures are only counted)",
                    thread.getName(), what, job, failure);
        }
    }

    // ---- priority inheritance ----

    /** On this thread, after {@code job} was parked: lend our priority to whoever runs its component. */
    private void lendPriorityFor(Job job) {
        ThreadGrant own = grant;
        if (own == null || !own.granted().isRealtime()) {
            return;
        }
        Object target = job.target();
        for (Dispatcher holder : context.dispatchers()) {
            if (holder != this && holder.runningTarget == target) {
                holder.inheritPriority(own.granted(), target);
            }
        }
    }

    /** From a waiting dispatcher's thread: raise this thread while it still runs {@code target}. */
    void inheritPriority(ThreadPolicy donor, Object target) {
        ThreadGrant own = grant;
        if (own == null || own.osThreadId() <= 0 || donor.priority() <= basePriority(own)) {
            return;
        }
        boostLock.lock();
        try {
            int previous = boostedPriority;
            if (donor.priority() <= previous) {
                return;
            }
            // Announce before looking: endBoost() clears runningTarget before it reads
            // boostedPriority, so one of us sees the other (both are volatile).
            boostedPriority = donor.priority();
            if (runningTarget == target
                    && LinuxNative.setScheduler(own.osThreadId(), osPolicy(donor) | LinuxNative.SCHED_RESET_ON_FORK,
                            donor.priority()).ok()) {
                recorder.recordBoost();
            } else {
                boostedPriority = previous;
            }
        } finally {
            boostLock.unlock();
        }
    }

    /** On this thread, after a job: drop a lent priority back to our own. */
    private void endBoost() {
        boostLock.lock();
        try {
            if (boostedPriority != 0) {
                ThreadPolicy base = grant.granted();
                LinuxNative.setScheduler(0, osPolicy(base) | (base.isRealtime() ? LinuxNative.SCHED_RESET_ON_FORK : 0),
                        base.priority());
                boostedPriority = 0;
            }
        } finally {
            boostLock.unlock();
        }
    }

    private static int basePriority(ThreadGrant grant) {
        return grant.granted().isRealtime() ? grant.granted().priority() : 0;
    }

    private static int osPolicy(ThreadPolicy policy) {
        return switch (policy.policy()) {
            case OTHER -> LinuxNative.SCHED_OTHER;
            case FIFO -> LinuxNative.SCHED_FIFO;
            case RR -> LinuxNative.SCHED_RR;
        };
    }

    // ---- shutdown (called by the scheduler's shutdown thread) ----

    /** Wakes the thread so it sees the ABORTED state. */
    public void wake() {
        LockSupport.unpark(thread);
    }

    public Thread thread() {
        return thread;
    }

    /**
     * Removes every queued job. Only safe once the thread has ended (its heap is private); while
     * it still runs, only the intake is taken and the heap's size is returned in {@code stranded}.
     */
    public List<Job> drain(int[] stranded) {
        var jobs = new ArrayList<Job>();
        moveIntakeTo(jobs);
        if (!thread.isAlive()) {
            jobs.addAll(ready);
            ready.clear();
        } else {
            stranded[0] += ready.size();
        }
        return jobs;
    }

    public int id() {
        return id;
    }
}
