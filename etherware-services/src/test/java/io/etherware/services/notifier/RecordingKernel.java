package io.etherware.services.notifier;

import io.etherware.core.component.Component;
import io.etherware.core.component.Shell;
import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.NodeStats;
import io.etherware.core.kernel.ProfileRegistry;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.kernel.RemoteRoute;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Tick;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.AtomicLong;

/**
 * A kernel that records what is sent, with a registry of fake local components whose finished
 * counters the test moves (a receiver that consumes, or one that stalls). Thread-safe.
 */
final class RecordingKernel implements Kernel {

    private final io.etherware.core.message.ContentsTypes contentsTypes = new io.etherware.core.message.ContentsTypes();

    private final NodeClock clock;
    private final AtomicLong messageSequence = new AtomicLong();
    private final List<Message> sent = new ArrayList<>();
    private final List<Long> sentAtNs = new ArrayList<>();
    private final Map<Profile, Endpoint> endpoints = new ConcurrentHashMap<>();
    /** Receivers that consume every Tick at once (their counter moves on send). */
    private final Map<Profile, FakeShell> autoConsume = new ConcurrentHashMap<>();

    private volatile boolean refuseSends;

    RecordingKernel(NodeClock clock) {
        this.clock = clock;
    }

    /** A local receiver; {@code consumes}: its counter moves with every message sent to it. */
    FakeShell addReceiver(Profile profile, boolean consumes) {
        var shell = new FakeShell(profile);
        endpoints.put(profile, new Endpoint.Local(shell));
        if (consumes) {
            autoConsume.put(profile, shell);
        }
        return shell;
    }

    void addRemote(Profile profile) {
        endpoints.put(profile, new Endpoint.Remote(message -> { }));
    }

    void removeReceiver(Profile profile) {
        endpoints.remove(profile);
        autoConsume.remove(profile);
    }

    /** Every message sent so far, in order. */
    synchronized List<Message> sent() {
        return List.copyOf(sent);
    }

    /** The Ticks sent so far, in order. */
    List<Tick> ticks() {
        return sent().stream().map(message -> message.contentsAs(Tick.class)).toList();
    }

    /** The clock's reading when each message was sent, in order. */
    synchronized List<Long> sentAtNs() {
        return List.copyOf(sentAtNs);
    }

    synchronized int sentCount() {
        return sent.size();
    }

    /** Makes {@link #send} throw, as a kernel that is not started does. */
    void refuseSends(boolean refuse) {
        refuseSends = refuse;
    }

    @Override
    public synchronized void send(Message message) {
        if (refuseSends) {
            throw new IllegalStateException("node 'test' is not started: call start() before sending");
        }
        sent.add(message);
        sentAtNs.add(clock.nanoTime());
        FakeShell shell = autoConsume.get(message.profile());
        if (shell != null) {
            shell.finishOne();
        }
    }

    @Override
    public String nodeId() {
        return "test";
    }

    @Override
    public Profile profile() {
        return Profile.of("etherware.node", "id", "test");
    }

    @Override
    public NodeClock clock() {
        return clock;
    }

    @Override
    public io.etherware.core.message.ContentsTypes contentsTypes() {
        return contentsTypes;
    }

    @Override
    public ProfileRegistry registry() {
        return new ProfileRegistry() {
            @Override
            public Endpoint resolve(Profile profile) {
                Endpoint endpoint = endpoints.get(profile);
                if (endpoint == null) {
                    throw new ProfileResolutionException(profile, List.of(), "no profile matches '" + profile + "'");
                }
                return endpoint;
            }

            @Override
            public Set<Profile> profiles() {
                return Set.copyOf(endpoints.keySet());
            }

            @Override
            public void registerRemote(Profile profile, RemoteRoute route) {
                endpoints.put(profile, new Endpoint.Remote(route));
            }

            @Override
            public boolean unregisterRemote(Profile profile) {
                return endpoints.remove(profile) != null;
            }

            @Override
            public boolean replaceRemote(Profile profile, RemoteRoute expected, RemoteRoute replacement) {
                return endpoints.get(profile) instanceof Endpoint.Remote remote && remote.route() == expected
                        && endpoints.replace(profile, remote, new Endpoint.Remote(replacement));
            }

            @Override
            public void addListener(Listener listener) {
                throw new UnsupportedOperationException("the Notifier does not listen to the registry");
            }

            @Override
            public boolean removeListener(Listener listener) {
                return false;
            }
        };
    }

    @Override
    public MessageId newMessageId() {
        return new MessageId(nodeId(), messageSequence.getAndIncrement());
    }

    @Override
    public CompletableFuture<Message> request(Message request, long timeoutNs) {
        throw new UnsupportedOperationException();
    }

    @Override
    public Scheduler scheduler() {
        throw new UnsupportedOperationException("the Notifier does not ask for the node's scheduler");
    }

    @Override
    public CompletableFuture<Void> closedFuture() {
        return new CompletableFuture<>(); // this test double never closes
    }

    @Override
    public NodeStats stats() {
        return new NodeStats(nodeId(), 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);
    }

    /** A local component's shell whose finished-message counter the test controls. */
    static final class FakeShell implements Shell {
        private final Profile profile;
        private final AtomicLong handled = new AtomicLong();

        FakeShell(Profile profile) {
            this.profile = profile;
        }

        void finishOne() {
            handled.incrementAndGet();
        }

        @Override
        public Profile profile() {
            return profile;
        }

        @Override
        public State state() {
            return State.RUNNING;
        }

        @Override
        public long handledCount() {
            return handled.get();
        }

        @Override
        public long failedCount() {
            return 0;
        }

        @Override
        public long restartCount() {
            return 0;
        }

        @Override
        public long lastHandlingNs() {
            return 0;
        }

        @Override
        public Class<? extends Component> logicType() {
            return Component.class;
        }
    }
}
