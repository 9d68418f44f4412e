package io.etherware.core.kernel.internal;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentState;
import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.RemoteRoute;
import io.etherware.core.kernel.SwapTimings;
import io.etherware.core.time.Durations;
import io.etherware.core.time.NodeClock;
import java.time.Duration;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;
import java.util.function.LongConsumer;
import java.util.function.Supplier;

/**
 * What the node does to a running component at its message boundaries for upgrade and migration:
 * hold (at once, or once it is quiescent), swap its logic, take its state, relocate it behind a
 * route. {@link KernelCore} resolves the component and keeps the node's books (which components
 * it hosts); this class only drives the component's shell.
 *
 * <p>Thread-safety: any thread; each action runs on the thread that owns the component at its
 * boundary (see {@link ComponentGate#atBoundary}).
 */
final class Reconfiguration {

    private final NodeClock clock;
    private final ProfileTable registry;
    private final RequestTable timer;

    /**
     * @param timer schedules the settle wait's last try (a boundary for an idle component)
     */
    Reconfiguration(NodeClock clock, ProfileTable registry, RequestTable timer) {
        this.clock = clock;
        this.registry = registry;
        this.timer = timer;
    }

    /** Holds {@code shell} at its next boundary. */
    CompletableFuture<Void> holdAsync(LocalShell shell) {
        var held = new CompletableFuture<Void>();
        shell.atBoundary(() -> shell.hold(held));
        return held;
    }

    /**
     * Holds {@code shell} at its next boundary where it awaits no outcome and has no message of
     * another component queued, or after {@code settleWait}.
     */
    CompletableFuture<Void> holdAsync(LocalShell shell, Duration settleWait) {
        var held = new CompletableFuture<Void>();
        whenSettled(shell, () -> shell.hold(held), settleWait, true, held);
        return held;
    }

    /**
     * Swaps the logic of {@code shell} at its next boundary where it awaits no outcome, or after
     * {@code settleWait} (zero: at the next boundary).
     *
     * @param onFirstHandling told of the new logic's first handling, or null
     */
    CompletableFuture<SwapTimings> swapAsync(LocalShell shell, Supplier<? extends Component> factory,
                                             LongConsumer onFirstHandling, Duration settleWait) {
        Objects.requireNonNull(factory, "factory");
        var swapped = new CompletableFuture<SwapTimings>();
        Runnable swap = () -> {
            if (!swapped.isDone()) {
                shell.swap(factory, swapped, onFirstHandling);
            }
        };
        whenSettled(shell, swap, settleWait, false, swapped);
        return swapped;
    }

    /** The state of {@code shell} at its next boundary. */
    CompletableFuture<ComponentState> snapshotAsync(LocalShell shell) {
        var state = new CompletableFuture<ComponentState>();
        shell.atBoundary(() -> {
            try {
                state.complete(shell.snapshotNow());
            } catch (Throwable e) {
                state.completeExceptionally(e);
            }
        });
        return state;
    }

    /**
     * Stops {@code shell} at its next boundary and points its profile at {@code route} once the
     * messages kept or queued for it have gone there first; {@code detach} runs at that boundary,
     * before anything is forwarded.
     */
    CompletableFuture<Void> relocateAsync(LocalShell shell, RemoteRoute route, Runnable detach) {
        var relocated = new CompletableFuture<Void>();
        shell.atBoundary(() -> {
            try {
                detach.run();
                shell.relocate(registry, new Endpoint.Remote(route), relocated);
            } catch (RuntimeException e) {
                relocated.completeExceptionally(e);
            }
        });
        return relocated;
    }

    /**
     * Runs {@code action} at a boundary of {@code shell} where it is quiescent (it awaits no
     * outcome of its requests; if {@code drains}, no message of another component is queued for
     * it either: see {@link SettleQueue}), or at the first boundary after {@code settleWait} (a
     * timer makes one if the component is idle then); {@code done} says when no further try is
     * needed.
     */
    private void whenSettled(LocalShell shell, Runnable action, Duration settleWait, boolean drains,
                             CompletableFuture<?> done) {
        if (Objects.requireNonNull(settleWait, "settleWait").isNegative()) {
            throw new IllegalArgumentException("settleWait=" + settleWait + " must not be negative");
        }
        long waitNs = Durations.toNs("settleWait", settleWait);
        long deadlineNs = clock.nanoTime() + waitNs;
        shell.atBoundary(() -> shell.whenSettled(action, deadlineNs, waitNs == 0, drains));
        if (waitNs > 0) {
            // Without a boundary after the deadline (an idle component waiting for a lost reply).
            timer.schedule(() -> {
                if (!done.isDone()) {
                    shell.atBoundary(() -> shell.settleDeadline(action));
                }
            }, waitNs);
        }
    }
}
