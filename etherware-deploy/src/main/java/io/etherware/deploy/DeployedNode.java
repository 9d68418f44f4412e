package io.etherware.deploy;

import io.etherware.core.component.Component;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.message.ContentsTypes;
import io.etherware.deploy.internal.XmlElement;
import io.etherware.deploy.view.LiveSignals;
import io.etherware.deploy.view.NodeView;
import io.etherware.services.management.ManagementService;
import io.etherware.services.network.NetworkMessenger;
import io.etherware.services.notifier.Notifier;
import io.etherware.services.notifier.Subscription;
import io.etherware.services.status.Status;
import io.etherware.services.status.StatusService;
import java.io.IOException;
import java.net.InetSocketAddress;
import java.time.Duration;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Deque;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.function.Supplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * A node running from a {@link Deployment}. {@link #start} opens the components' resources
 * (through their factories), builds the node with every component, starts it, then its Notifier,
 * its network, its management service, its status service ({@code etherware.status[node=<id>]},
 * which the control tool asks) and its live view ({@link NodeView}, if the file has a
 * {@code <view>}); each Notifier subscription starts as soon as its target resolves (at once for a
 * component of this node, when a peer announces it otherwise), on a thread of its own that waits
 * for them. {@link #close} stops them in the reverse order: the view, subscriptions and Notifier,
 * network, node (with the management service and components), then the factories' resources.
 *
 * <p>Thread-safe: {@link #close} may be called from any thread (a shutdown hook), more than once.
 */
public final class DeployedNode implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(DeployedNode.class);
    /** How long the subscription thread waits per round for targets that do not resolve yet. */
    private static final Duration RESOLVE_ROUND = Duration.ofMillis(200);

    private final Deployment deployment;
    private final Deque<AutoCloseable> resources;
    private final EtherwareNode node;
    private final Notifier notifier;
    private final NetworkMessenger network;
    private final LiveSignals signals;
    private final NodeView view;
    private final Thread subscriber;
    private volatile boolean closing;

    private DeployedNode(Deployment deployment, Deque<AutoCloseable> resources, EtherwareNode node,
            Notifier notifier, NetworkMessenger network, LiveSignals signals, NodeView view) {
        this.deployment = deployment;
        this.resources = resources;
        this.node = node;
        this.notifier = notifier;
        this.network = network;
        this.signals = signals;
        this.view = view;
        List<Subscription> subscriptions = deployment.notifier().map(Deployment.NotifierPlan::subscriptions)
                .orElse(List.of());
        subscriber = subscriptions.isEmpty() ? null : Thread.ofPlatform().daemon()
                .name("deploy-subscriptions@" + deployment.nodeId()).unstarted(() -> subscribeWhenResolvable(
                        subscriptions));
    }

    /**
     * Starts the node {@code deployment} describes.
     *
     * @param deployment the checked deployment
     * @return the running node
     * @throws DeploymentException if a component's factory refuses its settings or cannot open what
     *                             it needs, or the node, its network, management service or view
     *                             cannot start; whatever was started is closed again first
     */
    public static DeployedNode start(Deployment deployment) throws DeploymentException {
        Deque<AutoCloseable> resources = new ArrayDeque<>();
        EtherwareNode node = null;
        NetworkMessenger network = null;
        var signals = new LiveSignals();
        try {
            var types = new ContentsTypes();
            for (Deployment.ComponentPlan plan : deployment.components()) {
                plan.factory().registerContents(types);
            }
            var suppliers = new ArrayList<Supplier<? extends Component>>();
            for (Deployment.ComponentPlan plan : deployment.components()) {
                suppliers.add(create(deployment, plan, resources, signals));
            }
            node = EtherwareNode.builder().nodeId(deployment.nodeId()).scheduler(deployment.scheduler().factory())
                    .contentsTypes(types).build();
            for (int i = 0; i < suppliers.size(); i++) {
                node.add(deployment.components().get(i).profile(), suppliers.get(i));
            }
            node.start();
            EtherwareNode started = node;
            Notifier notifier = deployment.notifier().map(plan -> Notifier.install(started, plan.config()))
                    .orElse(null);
            if (deployment.network().isPresent()) {
                network = startNetwork(deployment, node);
            }
            NetworkMessenger messenger = network;
            deployment.management().ifPresent(config -> ManagementService.install(started, config, messenger));
            StatusService.install(node, network);
            NodeView view = deployment.view().isPresent()
                    ? startView(deployment, deployment.view().get(), node, network, signals) : null;
            var deployed = new DeployedNode(deployment, resources, node, notifier, network, signals, view);
            if (deployed.subscriber != null) {
                deployed.subscriber.start();
            }
            LOG.info("node {} started from {}: scheduler {}, {} component(s){}{}", deployment.nodeId(),
                    deployment.file(), deployment.scheduler().description(), deployment.components().size(),
                    network != null ? ", listening on " + network.localAddress() : "",
                    view != null ? ", view on " + view.url() : "");
            return deployed;
        } catch (DeploymentException | RuntimeException | Error e) {
            closeQuietly(network, "network");
            closeQuietly(node, "node");
            closeAll(resources);
            if (e instanceof DeploymentException deploymentException) {
                throw deploymentException;
            }
            if (e instanceof Error error && !(error instanceof LinkageError)) {
                throw error;
            }
            throw new DeploymentException(deployment.file(), 0, 0, "node " + deployment.nodeId() + " did not start: "
                    + e.getMessage(), e);
        }
    }

    private static NetworkMessenger startNetwork(Deployment deployment, EtherwareNode node)
            throws DeploymentException {
        var config = deployment.network().orElseThrow();
        if (config.isInsecureBeyondLoopback() && deployment.management().map(m -> m.allowUnauthenticatedLinks())
                .orElse(false)) {
            LOG.warn("node {}: plain TCP beyond loopback (insecure=\"true\") and a management service that trusts"
                    + " unauthenticated links (allowUnauthenticatedLinks=\"true\"): any host that reaches {} may"
                    + " claim to be a node of the access list; use <tls> between machines", deployment.nodeId(),
                    config.listenAddress());
        }
        try {
            return NetworkMessenger.start(node, config);
        } catch (RuntimeException e) {
            throw new DeploymentException(deployment.file(), 0, 0, "<network listen=\"" + config.listenAddress()
                    .getHostString() + ":" + config.listenAddress().getPort() + "\">: the network did not start ("
                    + e.getMessage() + "); if another process listens there, stop it or choose another address"
                    + " (-P, or port 0 for any free port)", e);
        }
    }

    private static NodeView startView(Deployment deployment, Deployment.ViewPlan plan, EtherwareNode node,
            NetworkMessenger network, LiveSignals signals) throws DeploymentException {
        try {
            return NodeView.start(plan.config(), () -> Status.snapshot(node, network), signals);
        } catch (IOException e) {
            var listen = plan.config().listen();
            throw new DeploymentException(deployment.file(), plan.line(), 0, "<view listen=\""
                    + listen.getAddress().getHostAddress() + ":" + listen.getPort() + "\">: cannot listen there ("
                    + e + "); choose a free port, or 0 for any", e);
        }
    }

    private static Supplier<? extends Component> create(Deployment deployment, Deployment.ComponentPlan plan,
            Deque<AutoCloseable> resources, LiveSignals signals) throws DeploymentException {
        Supplier<? extends Component> supplier;
        try {
            supplier = plan.factory().create(plan.settings(), new ComponentFactory.Resources() {
                @Override
                public <T extends AutoCloseable> T closeAfterNode(T resource) {
                    resources.push(resource);
                    return resource;
                }

                @Override
                public LiveSignals signals() {
                    return signals;
                }
            });
        } catch (RuntimeException | LinkageError e) {
            throw new DeploymentException(deployment.file(), plan.line(), 0, "<component profile=\"" + plan.profile()
                    + "\" class=\"" + plan.className() + "\">: its factory failed: " + e, e);
        }
        if (supplier == null) {
            throw new DeploymentException(deployment.file(), plan.line(), 0, "<component profile=\"" + plan.profile()
                    + "\">: " + plan.className() + ".create returned null", null);
        }
        Map<String, XmlElement> unread = plan.settings().unread();
        if (!unread.isEmpty()) {
            var first = unread.entrySet().iterator().next();
            throw new DeploymentException(deployment.file(), first.getValue().line(), first.getValue().column(),
                    "<setting name=\"" + first.getKey() + "\"> is not a setting of " + plan.className()
                            + "; it reads " + plan.settings().readNames() + ": check the spelling", null);
        }
        return supplier;
    }

    /** {@return the deployment this node runs} */
    public Deployment deployment() {
        return deployment;
    }

    /** {@return the node} */
    public EtherwareNode node() {
        return node;
    }

    /** {@return the network messenger, if the deployment has a {@code <network>}} */
    public Optional<NetworkMessenger> network() {
        return Optional.ofNullable(network);
    }

    /** {@return the Notifier, if the deployment has a {@code <notifier>}} */
    public Optional<Notifier> notifier() {
        return Optional.ofNullable(notifier);
    }

    /**
     * Where the network listens, if the deployment has a {@code <network>}.
     *
     * @return the bound address (the real port where the file said 0)
     */
    public Optional<InetSocketAddress> listenAddress() {
        return network().map(NetworkMessenger::localAddress);
    }

    /** {@return the node's live signals, which its factories publish into} */
    public LiveSignals signals() {
        return signals;
    }

    /**
     * Where the live view listens, if the deployment has a {@code <view>}.
     *
     * @return the bound address (the real port where the file said 0)
     */
    public Optional<InetSocketAddress> viewAddress() {
        return Optional.ofNullable(view).map(NodeView::address);
    }

    /**
     * The live view's page, if the deployment has a {@code <view>}.
     *
     * @return e.g. {@code http://127.0.0.1:8080/}
     */
    public Optional<String> viewUrl() {
        return Optional.ofNullable(view).map(NodeView::url);
    }

    /**
     * Stops the node in order: the view, subscriptions and Notifier, network, node, the factories'
     * resources. Idempotent; a step that fails is logged and the next still runs.
     */
    @Override
    public synchronized void close() {
        if (closing) {
            return;
        }
        closing = true;
        LOG.info("node {} closing", deployment.nodeId());
        closeQuietly(view, "view");
        if (subscriber != null) {
            subscriber.interrupt();
            try {
                subscriber.join(Duration.ofSeconds(5));
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
        closeQuietly(notifier, "notifier");
        closeQuietly(network, "network");
        closeQuietly(node, "node");
        closeAll(resources);
        LOG.info("node {} closed", deployment.nodeId());
    }

    private void subscribeWhenResolvable(List<Subscription> subscriptions) {
        var waiting = new ArrayList<>(subscriptions);
        try {
            while (!waiting.isEmpty() && !closing) {
                for (var it = waiting.iterator(); it.hasNext(); ) {
                    Subscription subscription = it.next();
                    boolean resolvable = resolvesHere(subscription)
                            || network != null && network.awaitResolvable(subscription.target(), RESOLVE_ROUND);
                    if (resolvable && !closing) {
                        notifier.subscribe(subscription);
                        LOG.info("subscription {}: Ticks every {} µs to {} started", subscription.name(),
                                subscription.qos().periodNs() / 1_000, subscription.target());
                        it.remove();
                    }
                }
                if (network == null && !waiting.isEmpty()) {
                    LOG.warn("subscription(s) {} target no component of this node and the node has no network: they"
                            + " never start", waiting.stream().map(Subscription::name).toList());
                    return;
                }
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt(); // closing
        }
    }

    private boolean resolvesHere(Subscription subscription) {
        try {
            node.registry().resolve(subscription.target());
            return true;
        } catch (ProfileResolutionException e) {
            return false;
        }
    }

    private static void closeAll(Deque<AutoCloseable> resources) {
        while (!resources.isEmpty()) {
            closeQuietly(resources.pop(), "resource");
        }
    }

    private static void closeQuietly(AutoCloseable closeable, String what) {
        if (closeable == null) {
            return;
        }
        try {
            closeable.close();
        } catch (Exception e) {
            LOG.warn("closing the {} {} failed: {}", what, closeable, e.toString());
        }
    }
}
