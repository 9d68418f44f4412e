package io.etherware.services.management;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentState;
import io.etherware.core.component.Shell;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.NodeStats;
import io.etherware.core.kernel.ProfileRegistry;
import io.etherware.core.kernel.RemoteRoute;
import io.etherware.core.kernel.SwapTimings;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Origin;
import io.etherware.core.message.Profile;
import io.etherware.core.time.NodeClock;
import java.util.concurrent.CompletableFuture;
import java.util.function.LongConsumer;
import java.util.function.Supplier;

/**
 * The kernel a test's NetworkMessenger is given: it stands in for the network layer's part of the
 * {@link Origin} contract until that layer sets origins itself. A message the messenger hands over
 * without an origin, made on another node, gets {@code Origin.direct(<its id's node>, false)}: what
 * a plain-TCP connection, which refuses a direct message whose id names another node than its
 * peer, would establish. Once the messenger sets origins, this changes nothing.
 *
 * <p>Thread-safety: as the kernel it wraps.
 */
final class NetworkOrigins implements Kernel {

    private final Kernel kernel;

    NetworkOrigins(Kernel kernel) {
        this.kernel = kernel;
    }

    @Override
    public void send(Message message) {
        boolean fromElsewhere = message.origin() == null && !message.messageId().nodeId().equals(kernel.nodeId());
        kernel.send(fromElsewhere ? message.withOrigin(Origin.direct(message.messageId().nodeId(), false)) : message);
    }

    @Override
    public String nodeId() {
        return kernel.nodeId();
    }

    @Override
    public Profile profile() {
        return kernel.profile();
    }

    @Override
    public NodeClock clock() {
        return kernel.clock();
    }

    @Override
    public ProfileRegistry registry() {
        return kernel.registry();
    }

    @Override
    public MessageId newMessageId() {
        return kernel.newMessageId();
    }

    @Override
    public CompletableFuture<Message> request(Message request, long timeoutNs) {
        return kernel.request(request, timeoutNs);
    }

    @Override
    public CompletableFuture<Void> holdAsync(Profile profile) {
        return kernel.holdAsync(profile);
    }

    @Override
    public void release(Profile profile) {
        kernel.release(profile);
    }

    @Override
    public CompletableFuture<Void> swapAsync(Profile profile, Supplier<? extends Component> factory) {
        return kernel.swapAsync(profile, factory);
    }

    @Override
    public CompletableFuture<SwapTimings> swapAsync(Profile profile, Supplier<? extends Component> factory,
                                                    LongConsumer onFirstHandling) {
        return kernel.swapAsync(profile, factory, onFirstHandling);
    }

    @Override
    public CompletableFuture<ComponentState> snapshotAsync(Profile profile) {
        return kernel.snapshotAsync(profile);
    }

    @Override
    public CompletableFuture<Void> relocateAsync(Profile profile, RemoteRoute route) {
        return kernel.relocateAsync(profile, route);
    }

    @Override
    public Shell addHeld(Profile profile, Profile arrival, Supplier<? extends Component> factory,
                         LongConsumer onFirstHandling) {
        return kernel.addHeld(profile, arrival, factory, onFirstHandling);
    }

    @Override
    public void admit(Profile arrival, long forwardedCount) {
        kernel.admit(arrival, forwardedCount);
    }

    @Override
    public CompletableFuture<Void> removeAsync(Profile profile) {
        return kernel.removeAsync(profile);
    }

    @Override
    public NodeStats stats() {
        return kernel.stats();
    }
}
