package io.etherware.services.management;

import io.etherware.core.component.Shell;
import io.etherware.core.kernel.ComponentHost;
import io.etherware.core.kernel.SwapTimings;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.services.management.AccessRule.Operation;
import io.etherware.services.management.ManagementFailure.Reason;
import io.etherware.services.management.OperationQueue.Permit;
import io.etherware.services.management.internal.ImplementationLoader;
import io.etherware.services.management.internal.LoadFailure;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionException;
import java.util.concurrent.Executor;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

/**
 * The upgrades a management service serves, in the steps listed on {@link ManagementService}: the
 * access check and the hand-over to the worker on the service's dispatcher ({@link #accept}),
 * resolving and loading on the worker, the swap back on the dispatcher ({@link #swap}), and the
 * answer on the worker once the new logic's first message began.
 *
 * <p>Threading: {@link #accept} and {@link #swap} run on the service's dispatcher and never block
 * or load code; the rest runs on the worker, one upgrade at a time. Takes no lock.
 */
final class Upgrades {

    private static final String UPGRADE = "upgrade";

    private final ManagementContext service;
    private final ComponentHost kernel;
    private final ManagementConfig config;
    private final ImplementationLoader loader;
    private final OperationQueue worker;
    /** Where a swap's outcome is answered: the worker, or inline once it stopped. */
    private final Executor continuations;

    /**
     * @param loader loads and checks the new implementations
     * @param worker the service's worker, which loads and answers
     */
    Upgrades(ManagementContext service, ImplementationLoader loader, OperationQueue worker) {
        this.service = service;
        this.kernel = service.kernel();
        this.config = service.config();
        this.loader = loader;
        this.worker = worker;
        this.continuations = worker.continuations();
    }

    /** Dispatcher: refuses what the access list does not allow, else hands the loading to the worker. */
    void accept(Message message, UpgradeRequest request) {
        long receivedNs = kernel.clock().nanoTime();
        if (service.refused(message, Operation.UPGRADE, UPGRADE, request.target())) {
            return;
        }
        worker.submit(permit -> upgrade(message, request, receivedNs, permit),
                (reason, error) -> fail(message, request, reason, error));
    }

    /**
     * An upgrade loaded by the worker, handed back to the service's dispatcher as a message to
     * itself, carrying the request's QoS: the swap then starts at the request's priority (paper
     * Section VI-C1). Never leaves the node (it is not a registered contents type).
     */
    record Prepared(Message message, UpgradeRequest request, Shell shell, ImplementationLoader.Loaded loaded,
                    long loadNs, long receivedNs, CompletableFuture<Long> firstHandling,
                    CompletableFuture<Void> swapped)
            implements Contents {
    }

    /** Worker thread: resolve and load, then hand the swap back to the dispatcher. */
    private void upgrade(Message message, UpgradeRequest request, long receivedNs, Permit permit) {
        Shell shell;
        try {
            shell = service.localShell(request.target());
        } catch (LoadFailure e) {
            permit.release();
            fail(message, request, e.reason(), e.getMessage());
            return;
        }
        long loadStartNs = kernel.clock().nanoTime();
        ImplementationLoader.Loaded loaded;
        try {
            loaded = loader.load(request.className(), request.jarPath(), request.configuration());
        } catch (LoadFailure e) {
            permit.release();
            fail(message, request, e.reason(), e.getMessage());
            return;
        } catch (RuntimeException | LinkageError e) {
            permit.release();
            fail(message, request, Reason.CLASS_NOT_LOADABLE, "loading '" + request.className() + "' failed: " + e);
            return;
        }
        long loadNs = kernel.clock().nanoTime() - loadStartNs;
        // Armed here, not on the dispatcher: the timer's bookkeeping stays out of the swap gap.
        var firstHandling = new CompletableFuture<Long>();
        firstHandling.completeOnTimeout(SwapTimings.UNKNOWN_NS, config.firstMessageWaitNs(), TimeUnit.NANOSECONDS);
        var swapped = new CompletableFuture<Void>();
        try {
            service.context().send(service.context().self(), new Prepared(message, request, shell, loaded, loadNs,
                    receivedNs, firstHandling, swapped), message.qos());
        } catch (RuntimeException e) {
            loaded.discard();
            permit.release();
            fail(message, request, Reason.SERVICE_FAILED, "the management service could not schedule the swap: " + e);
            return;
        }
        // One operation at a time: the next waits until this swap is done (or given up waiting for).
        try {
            swapped.get(config.settleWaitNs() + config.migrationStepTimeoutNs(), TimeUnit.NANOSECONDS);
        } catch (ExecutionException | TimeoutException e) {
            // Answered by the swap's own continuation; the next operation may go.
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    /**
     * Dispatcher: starts the swap without waiting for it. If the component is between messages
     * the swap runs here and now; otherwise the kernel runs it on the component's dispatcher
     * when its current message is done. Nothing else happens here, because until the swap is over
     * (and, on a shared dispatcher, until this handler returns) the component's next message waits:
     * the answer is assembled on the worker once the new logic has begun its first message.
     */
    void swap(Prepared prepared) {
        Message message = prepared.message();
        UpgradeRequest request = prepared.request();
        Shell shell = prepared.shell();
        ImplementationLoader.Loaded loaded = prepared.loaded();
        String oldImplementation = shell.logicType().getName();
        CompletableFuture<Long> firstHandling = prepared.firstHandling();
        CompletableFuture<SwapTimings> swap;
        try {
            // When no request of the old logic is in flight (within the settle wait): its outcome
            // then reaches the callback that waits for it instead of a replaced logic.
            swap = kernel.swapAsync(shell.profile(), loaded.factory(), firstHandling::complete,
                    Duration.ofNanos(config.settleWaitNs()));
        } catch (RuntimeException e) {
            loaded.discard();
            prepared.swapped().complete(null);
            fail(message, request, Reason.UNKNOWN_COMPONENT, "component '" + shell.profile() + "' went away: " + e);
            return;
        }
        // Not ...Async: on success this runs inside the swap and must cost nothing; only a failure
        // (the slow path) goes to the worker.
        swap.whenComplete((timings, error) -> {
            prepared.swapped().complete(null);
            if (error != null) {
                continuations.execute(() -> rolledBack(message, request, shell, loaded, oldImplementation, error));
            }
        });
        // Runs when both are known: the new logic's first message began (or the wait ended).
        swap.thenAcceptBothAsync(firstHandling, (timings, firstNs) -> {
            service.jarLoaders().installed(shell.profile(), loaded.loader());
            answer(message, shell.profile(), oldImplementation, loaded, prepared.loadNs(), timings, firstNs,
                    prepared.receivedNs());
        }, continuations);
    }

    private void rolledBack(Message message, UpgradeRequest request, Shell shell, ImplementationLoader.Loaded loaded,
                            String oldImplementation, Throwable error) {
        loaded.discard();
        Throwable cause = error instanceof CompletionException && error.getCause() != null ? error.getCause() : error;
        fail(message, request, Reason.ROLLED_BACK, "the swap of '" + shell.profile() + "' to "
                + loaded.type().getName() + " was rolled back, " + oldImplementation + " serves on: " + cause);
    }

    private void answer(Message message, Profile target, String oldImplementation, ImplementationLoader.Loaded loaded,
                        long loadNs, SwapTimings timings, long firstNs, long receivedNs) {
        long gapNs = firstNs == SwapTimings.UNKNOWN_NS || timings.lastOldHandlingEndNs() == SwapTimings.UNKNOWN_NS
                ? -1 : firstNs - timings.lastOldHandlingEndNs();
        long pauseNs = timings.pauseNs() == SwapTimings.UNKNOWN_NS ? -1 : timings.pauseNs();
        long totalNs = timings.swapEndNs() == SwapTimings.UNKNOWN_NS ? -1 : timings.swapEndNs() - receivedNs;
        var result = new UpgradeResult(target, oldImplementation, loaded.type().getName(), loaded.source(),
                timings.stateSchemaVersion(), loadNs, pauseNs, gapNs, totalNs);
        service.counters().upgraded.increment();
        service.log().info("upgraded '{}' from {} to {} ({}): load {} us, pause {} us, gap {}", target,
                oldImplementation, result.newImplementation(), result.source(), loadNs / 1_000, pauseNs / 1_000,
                gapNs < 0 ? "unknown" : gapNs / 1_000 + " us");
        service.reply(message, result);
    }

    private void fail(Message message, UpgradeRequest request, Reason reason, String error) {
        service.counters().failed.increment();
        service.log().warn("upgrade request {} of '{}' to {} failed ({}): {}", message.messageId(), request.target(),
                request.className(), reason, error);
        service.reply(message, new ManagementFailure(UPGRADE, request.target(), reason, error));
    }
}
