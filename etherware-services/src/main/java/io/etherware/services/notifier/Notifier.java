package io.etherware.services.notifier;

import io.etherware.core.component.Component;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Profile;
import io.etherware.core.time.DeadlineSleeper;
import io.etherware.core.time.NodeClock;
import io.etherware.rt.platform.AbsoluteSleeper;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.PlatformRefusal;
import io.etherware.rt.platform.ThreadGrant;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.services.notifier.internal.ReleaseSleeper;
import io.etherware.services.notifier.internal.ReleaseSchedule;
import io.etherware.services.notifier.internal.Sleeper;
import io.etherware.services.notifier.internal.SubscriptionState;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.Optional;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ConcurrentLinkedQueue;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.LockSupport;
import java.util.function.Consumer;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The Notifier service of a node (paper Section III-C): time-driven messages, Ticks, that activate
 * components at the time they are supposed to run, periodically or once.
 *
 * <p>A Tick is a {@link io.etherware.core.message.Message} to the subscription's target with the
 * subscription's QoS and contents {@link io.etherware.core.message.Tick Tick(releaseNs, sequence,
 * periodNs)}: the scheduled release {@code t0 + sequence * periodNs} on the node's monotonic
 * clock, so a receiver can measure its own lateness. Release times are absolute and computed from
 * the sequence, so they never drift. A release that cannot be honoured is skipped and counted,
 * never made up with a burst of Ticks: one the thread reaches after the next release is already
 * due or {@link Subscription#maxLatenessNs()} late (default half a period), one whose target does
 * not resolve, and, with {@link Subscription#backPressure()}, one whose local receiver has not
 * finished a single message since the previous Tick. {@link #stats(String)} counts each kind and
 * records the lateness (send time minus release) of every Tick sent.
 *
 * <p>One platform thread serves every subscription from a priority queue of next releases. It
 * runs at the OS priority of {@link NotifierConfig#threadPolicy()} (default SCHED_FIFO 82, above
 * every dispatcher of Table II; refused, it warns once and runs on), parks until each release and,
 * if configured, spins the last few µs.
 *
 * <p>Two ways in: this Java API, and the component {@link #component()} registered under
 * {@link #profile()}, which components use by message ({@link TickSubscribe},
 * {@link TickUnsubscribe}, {@link TickRetarget}, answered with {@link NotifierReply}).
 * {@link #install} does both for a node.
 *
 * <p>Thread-safety: every method may be called from any thread, including dispatcher threads.
 * {@link #unsubscribe} and {@link #retarget} take effect before they return: no Tick goes out
 * under the old settings afterwards.
 */
public final class Notifier implements AutoCloseable {

    /** The role of every Notifier's profile. */
    public static final String ROLE = "etherware.notifier";

    private static final Logger LOG = LoggerFactory.getLogger(Notifier.class);
    private static final long START_TIMEOUT_NS = TimeUnit.SECONDS.toNanos(10);
    private static final long STOP_TIMEOUT_MS = 5_000;

    private final Kernel kernel;
    private final NotifierConfig config;
    private final NodeClock clock;
    private final Sleeper sleeper;
    private final String sleepMethod;
    private final Profile profile;
    private final ReleaseSchedule schedule;
    private final ConcurrentHashMap<String, SubscriptionState> subscriptions = new ConcurrentHashMap<>();
    private final ConcurrentLinkedQueue<SubscriptionState> intake = new ConcurrentLinkedQueue<>();
    private final AtomicLong subscriptionOrder = new AtomicLong();
    private final AtomicLong undeliverableNotices = new AtomicLong();
    private final CountDownLatch started = new CountDownLatch(1);
    private final Component component;
    private final Object lifecycle = new Object();
    /** Made once: a method reference in the release loop would be a new object on every pass. */
    private final Consumer<SubscriptionState> finished = this::onFinished;
    private Thread thread; // guarded by lifecycle
    private volatile boolean running;
    private volatile boolean closed;
    private volatile ThreadGrant grant;

    /**
     * A Notifier sending through {@code kernel} on the kernel's clock; not started: its thread
     * starts with {@link #start()}.
     *
     * @param kernel the kernel the Ticks are sent through; its clock is the release clock
     * @param config how the Notifier runs; its profile, if null, becomes {@link #profileFor(String)}
     *               of the kernel's node id
     */
    public Notifier(Kernel kernel, NotifierConfig config) {
        this(kernel, config, kernel.clock(), null);
    }

    /** For tests: another clock and way of sleeping (null: park on {@code clock}). */
    Notifier(Kernel kernel, NotifierConfig config, NodeClock clock, Sleeper sleeper) {
        this.kernel = Objects.requireNonNull(kernel, "kernel");
        this.config = Objects.requireNonNull(config, "config");
        registerContents(kernel.contentsTypes());
        this.clock = Objects.requireNonNull(clock, "clock");
        // AbsoluteSleeper falls back to parking (and says why) where the kernel sleep is not usable;
        // ReleaseSleeper parks anyway, so it gets a kernel sleeper only when it is one.
        DeadlineSleeper candidate = config.kernelSleep() ? AbsoluteSleeper.forClock(clock) : null;
        DeadlineSleeper kernelSleeper = candidate instanceof AbsoluteSleeper ? candidate : null;
        this.sleeper = sleeper != null ? sleeper : new ReleaseSleeper(clock, config.spinNs(), kernelSleeper);
        this.sleepMethod = sleeper != null ? "a test's sleeper" : kernelSleeper != null
                ? "parks, then " + AbsoluteSleeper.describe(kernelSleeper) + " for the last "
                        + ReleaseSleeper.KERNEL_WINDOW_NS / 1_000 + " us"
                : candidate != null ? AbsoluteSleeper.describe(candidate) : "LockSupport.parkNanos";
        this.profile = config.profile() != null ? config.profile() : profileFor(kernel.nodeId());
        this.schedule = new ReleaseSchedule(kernel, clock, profile);
        this.component = new NotifierComponent(this);
    }

    /**
     * Creates a Notifier for {@code node}, registers its component under {@link #profile()}, and
     * ties its life to the node's: it starts with the component (at the node's start, or now if
     * the node runs) and closes when the node closes.
     *
     * @param node   the node to serve
     * @param config how the Notifier runs
     * @return the Notifier, already registered with {@code node}
     */
    public static Notifier install(EtherwareNode node, NotifierConfig config) {
        var notifier = new Notifier(node, config);
        node.add(notifier.profile(), notifier::component);
        node.closedFuture().whenComplete((ignored, failure) -> notifier.close());
        return notifier;
    }

    /**
     * The default profile of a node's Notifier.
     *
     * @param nodeId the node's id
     * @return {@code etherware.notifier[node=<nodeId>]}
     */
    public static Profile profileFor(String nodeId) {
        return Profile.of(ROLE, "node", nodeId);
    }

    /**
     * Registers the Notifier's message contents ({@code notifier.subscribe},
     * {@code notifier.unsubscribe}, {@code notifier.retarget}, {@code notifier.reply}) in
     * {@code types}. A Notifier does this for its node; a node that talks to a Notifier on another
     * node calls it for its own registry ({@code node.contentsTypes()}). Idempotent.
     *
     * @param types the registry to add the Notifier's types to
     * @throws IllegalArgumentException if {@code types} already has one of those names or records
     *                                  under another partner
     */
    public static void registerContents(ContentsTypes types) {
        types.register("notifier.subscribe", TickSubscribe.class);
        types.register("notifier.unsubscribe", TickUnsubscribe.class);
        types.register("notifier.retarget", TickRetarget.class);
        types.register("notifier.reply", NotifierReply.class);
    }

    /**
     * The profile of this Notifier's component, and the sender of its Ticks.
     *
     * @return {@link NotifierConfig#profile()}, or {@link #profileFor(String)} of the node when that
     *         is null
     */
    public Profile profile() {
        return profile;
    }

    /**
     * The configuration this Notifier was made with.
     *
     * @return the configuration, as given (its profile may be null; see {@link #profile()})
     */
    public NotifierConfig config() {
        return config;
    }

    /**
     * The message interface, to register under {@link #profile()} (one instance: restarts and
     * the factory return the same). Its {@code onStart} starts the Notifier.
     *
     * @return the component that serves {@link TickSubscribe}, {@link TickUnsubscribe} and
     *         {@link TickRetarget}
     */
    public Component component() {
        return component;
    }

    // ---------------------------------------------------------------- lifecycle

    /**
     * Starts the Notifier thread and waits until it has configured its OS priority; idempotent.
     * Subscriptions made before start release from then on (releases already past are skipped
     * and counted like any overrun). Blocks the caller for at most 10 s while the thread starts;
     * if it has not reported by then, a warning is logged and the Notifier runs on.
     *
     * @return this Notifier
     * @throws IllegalStateException if the Notifier was closed
     */
    public Notifier start() {
        Thread starting;
        synchronized (lifecycle) {
            if (closed) {
                throw new IllegalStateException("notifier " + profile + " is closed");
            }
            if (thread != null) {
                return this;
            }
            running = true;
            // Daemon: the application decides when the JVM ends, as for the dispatchers.
            starting = Thread.ofPlatform().name(config.threadName() + "@" + kernel.nodeId()).daemon(true).unstarted(this::run);
            thread = starting;
            starting.start();
        }
        try {
            if (!started.await(START_TIMEOUT_NS, TimeUnit.NANOSECONDS)) {
                LOG.warn("notifier {}: thread {} did not report its priority within {} s; it runs on", profile,
                        starting.getName(), TimeUnit.NANOSECONDS.toSeconds(START_TIMEOUT_NS));
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        return this;
    }

    /**
     * Whether the Notifier thread is releasing Ticks.
     *
     * @return true from {@link #start()} until {@link #close()}, or until the thread failed
     */
    public boolean isRunning() {
        return running;
    }

    /**
     * What the OS granted the Notifier thread: policy, priority, CPUs and any refusal.
     *
     * @return the grant, or empty before {@link #start()} has configured the thread
     */
    public Optional<ThreadGrant> threadGrant() {
        return Optional.ofNullable(grant);
    }

    /**
     * Stops the thread (waiting up to 5 s) and drops every subscription; idempotent. Ticks
     * already handed to the kernel are delivered as usual.
     */
    @Override
    public void close() {
        Thread stopping;
        synchronized (lifecycle) {
            if (closed) {
                return;
            }
            closed = true;
            running = false;
            stopping = thread;
        }
        subscriptions.values().forEach(SubscriptionState::cancel);
        subscriptions.clear();
        intake.clear();
        if (stopping != null && stopping != Thread.currentThread()) {
            LockSupport.unpark(stopping);
            try {
                stopping.join(STOP_TIMEOUT_MS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
            if (stopping.isAlive()) {
                LOG.warn("notifier {}: thread {} did not stop within {} ms", profile, stopping.getName(),
                        STOP_TIMEOUT_MS);
            }
        }
    }

    // ---------------------------------------------------------------- subscriptions

    /**
     * Adds a subscription; its first release is {@link Subscription#firstReleaseNs()}, or one
     * period from now (periodic) or now (one-shot) when unset. A periodic {@code t0} in the past
     * keeps its phase: the first release is the first grid point not before now.
     *
     * @param subscription what to release; its name must not be in use on this Notifier
     * @return the subscription as added, with its first release resolved
     * @throws IllegalArgumentException if a subscription of that name exists
     * @throws IllegalStateException    if the Notifier was closed
     */
    public Subscription subscribe(Subscription subscription) {
        Objects.requireNonNull(subscription, "subscription");
        if (closed) {
            throw new IllegalStateException("notifier " + profile + " is closed");
        }
        long nowNs = clock.nanoTime();
        Subscription resolved = subscription;
        if (subscription.firstReleaseNs() == Subscription.UNSET) {
            resolved = subscription.startingAt(nowNs + subscription.periodNs());
        }
        var state = new SubscriptionState(resolved, subscriptionOrder.getAndIncrement(), nowNs);
        if (subscriptions.putIfAbsent(resolved.name(), state) != null) {
            throw new IllegalArgumentException("subscription name '" + resolved.name() + "' is already in use on "
                    + profile + "; unsubscribe it first or choose another name");
        }
        intake.add(state);
        wakeThread();
        return resolved;
    }

    /**
     * Removes a subscription: no Tick of it goes out after this returns. May wait, briefly, for a
     * Tick of it that the Notifier thread is sending at that moment.
     *
     * @param name the subscription's name
     * @return its final accounting, or empty if no subscription has that name
     */
    public Optional<SubscriptionStats> unsubscribe(String name) {
        SubscriptionState state = subscriptions.remove(Objects.requireNonNull(name, "name"));
        if (state == null) {
            return Optional.empty();
        }
        state.cancel();
        schedule.awaitNotSending(state);
        return Optional.of(state.stats());
    }

    /**
     * Sends a subscription's Ticks to {@code newTarget} from its next release on, keeping its
     * release times and sequence (migration moves a component without breaking its rhythm). No
     * Tick goes to the old target after this returns (it may wait, briefly, for a Tick being sent).
     *
     * @param name      the subscription's name
     * @param newTarget the profile its Ticks go to from now on
     * @throws IllegalArgumentException if no subscription has that name
     */
    public void retarget(String name, Profile newTarget) {
        Objects.requireNonNull(newTarget, "newTarget");
        SubscriptionState state = subscriptions.get(Objects.requireNonNull(name, "name"));
        if (state == null) {
            throw new IllegalArgumentException("no subscription named '" + name + "' on " + profile
                    + " (a one-shot leaves once it has fired)");
        }
        state.retarget(newTarget);
        schedule.awaitNotSending(state);
    }

    /**
     * One subscription's accounting now.
     *
     * @param name the subscription's name
     * @return its accounting, or empty if no subscription has that name
     */
    public Optional<SubscriptionStats> stats(String name) {
        SubscriptionState state = subscriptions.get(Objects.requireNonNull(name, "name"));
        return state == null ? Optional.empty() : Optional.of(state.stats());
    }

    /**
     * Every current subscription's accounting.
     *
     * @return a new list, in no particular order; a one-shot that has fired is no longer in it
     */
    public List<SubscriptionStats> stats() {
        var all = new ArrayList<SubscriptionStats>();
        subscriptions.values().forEach(state -> all.add(state.stats()));
        return all;
    }

    /**
     * The current subscriptions.
     *
     * @return a new list, in no particular order, with each subscription's current target
     */
    public List<Subscription> subscriptions() {
        var all = new ArrayList<Subscription>();
        subscriptions.values().forEach(state -> all.add(state.subscription()));
        return all;
    }

    /**
     * Undeliverable notices the kernel returned to the Notifier's component for Ticks it could
     * not deliver after all (the target vanished between resolution and delivery).
     *
     * @return the count since construction
     */
    public long undeliverableNotices() {
        return undeliverableNotices.get();
    }

    void countUndeliverableNotice() {
        undeliverableNotices.incrementAndGet();
    }

    // ---------------------------------------------------------------- the Notifier thread

    private void wakeThread() {
        Thread current;
        synchronized (lifecycle) {
            current = thread;
        }
        if (current != null) {
            LockSupport.unpark(current);
        }
    }

    private void run() {
        schedule.claimThread();
        configureThread();
        try {
            while (running) {
                for (SubscriptionState state = intake.poll(); state != null; state = intake.poll()) {
                    schedule.add(state);
                }
                long nextReleaseNs = schedule.fireDue(finished);
                if (running && intake.isEmpty()) {
                    sleeper.sleepUntil(nextReleaseNs);
                }
            }
        } catch (Throwable failure) {
            running = false;
            LOG.error("notifier {}: thread {} failed; no more Ticks are released", profile,
                    Thread.currentThread().getName(), failure);
        }
    }

    private void onFinished(SubscriptionState state) {
        subscriptions.remove(state.name(), state);
    }

    private void configureThread() {
        ThreadPolicy requested = config.threadPolicy();
        CpuSet cpus = config.cpus();
        try {
            // Refusals are logged once per kind by the platform, with the errno and the fix.
            grant = Platform.current().configureCurrentThread(requested, cpus);
            LOG.info("notifier {}: {}; sleeps: {}", profile, grant.toLine(), sleepMethod);
        } catch (RuntimeException e) {
            LOG.error("notifier {}: could not configure its thread; it runs at the inherited priority", profile, e);
            grant = new ThreadGrant(Thread.currentThread().getName(), -1, requested, ThreadPolicy.NON_REALTIME, cpus,
                    CpuSet.inherit(), List.of(new PlatformRefusal("thread priority", requested.toString(), 38,
                            "ENOSYS", e.toString())));
        } finally {
            started.countDown();
        }
    }

    /**
     * How the Notifier's thread sleeps to a release, for reports.
     *
     * @return a short description: parks only, or parks and then sleeps in the kernel for the last
     *         stretch
     */
    public String sleepMethod() {
        return sleepMethod;
    }

    @Override
    public String toString() {
        return "Notifier[" + profile + "]";
    }
}
