package io.etherware.core.kernel.internal;

import io.etherware.core.kernel.Endpoint;
import io.etherware.core.message.Profile;
import io.etherware.core.scheduler.Job;
import java.util.ArrayList;
import java.util.Collections;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.function.Consumer;
import java.util.function.LongConsumer;

/**
 * The components a node hosts: their shells in registration order (the order they start in; they
 * stop in reverse at close), their profiles in the node's {@link ProfileTable}, the stopping of a
 * removed one, and the counters of every component the node has hosted, kept when one is removed
 * or moves away.
 *
 * <p>Owned by {@link KernelCore}, which makes the shells and decides when the node may take or
 * lose one.
 *
 * <p>Thread-safety: every method may be called from any thread. {@link KernelCore} calls
 * {@link #add}, {@link #addArrived} and {@link #remove} under its lifecycle lock, which orders
 * them with the node's start and close; the lists are copy-on-write, so readers take no lock.
 * {@link #stop} runs the removal on the thread that owns the component at its boundary (see
 * {@link ComponentGate#atBoundary}); {@link #closeAll} runs only at close. The retired counters
 * are guarded by their array, a lock taken by {@link #retire} and {@link #totals} alone, which
 * take no other lock while they hold it.
 */
final class ShellTable {

    /** The summed counters of the components a node has hosted. */
    record Totals(long handled, long failed, long restarts) {
    }

    private final ProfileTable registry;
    /** Registered components in registration order. */
    private final List<LocalShell> shells = new CopyOnWriteArrayList<>();
    private final List<LocalShell> registeredView = Collections.unmodifiableList(shells);
    /** Every component added and not yet removed or moved away, for the counters. */
    private final List<LocalShell> everAdded = new CopyOnWriteArrayList<>();
    /** The counters of the components removed or moved away (handled, failed, restarts); guarded by itself. */
    private final long[] retiredCounts = new long[3];

    ShellTable(ProfileTable registry) {
        this.registry = registry;
    }

    /** The registered components in registration order; iterating reads a snapshot. */
    List<LocalShell> registered() {
        return registeredView;
    }

    /** Registers {@code shell} under its profile and counts it hosted. */
    void add(LocalShell shell) {
        registry.register(shell.profile(), shell.endpoint());
        shells.add(shell);
        everAdded.add(shell);
    }

    /**
     * Registers a migrated component, not yet started, under {@code arrival} and under its own
     * profile (which displaces the route to the source), held until its admission.
     *
     * @param onFirstHandling told when it begins its first message
     * @throws IllegalArgumentException if its profile cannot be registered; nothing is then
     */
    void addArrived(LocalShell shell, Profile arrival, LongConsumer onFirstHandling) {
        // Held before it is reachable: nothing reaches it unheld. Once every message the source
        // forwarded to the arrival profile is in, the profile has served its turn.
        shell.arriveHeld(arrival, onFirstHandling, () -> registry.unregister(arrival, shell.endpoint()));
        registry.register(arrival, shell.endpoint());
        try {
            registry.register(shell.profile(), shell.endpoint()); // displaces the route to the source
        } catch (IllegalArgumentException e) {
            registry.unregister(arrival, shell.endpoint());
            throw e;
        }
        shells.add(shell);
        everAdded.add(shell);
    }

    /**
     * Unregisters the local component that {@code profile} names (its profile, or the arrival
     * profile of a migrated component) under all its profiles and takes it off the list; its
     * counters stay until {@link #retire}.
     *
     * @throws IllegalArgumentException if no local component has that profile
     */
    LocalShell remove(Profile profile) {
        Endpoint endpoint = registry.lookup(profile);
        if (!(endpoint instanceof Endpoint.Local local) || !registry.profiles().contains(profile)) {
            throw new IllegalArgumentException("no local component has profile '" + profile + "'");
        }
        LocalShell shell = (LocalShell) local.shell();
        // By its profile, or by the arrival profile of a migrated component: all go.
        registry.unregister(profile, endpoint);
        registry.unregister(shell.profile(), endpoint);
        ArrivalPen pen = shell.pen();
        if (pen != null) {
            registry.unregister(pen.arrival(), endpoint);
        }
        shells.remove(shell);
        return shell;
    }

    /**
     * Stops a component that {@link #remove} took off at its next message boundary (at once if it
     * never started) and retires it; completes when it has stopped.
     */
    CompletableFuture<Void> stop(LocalShell shell) {
        if (shell.cancelIfUnstarted()) {
            retire(shell);
            return CompletableFuture.completedFuture(null);
        }
        var stopped = new CompletableFuture<Void>();
        shell.atBoundary(() -> {
            shell.remove();
            retire(shell);
            stopped.complete(null);
        });
        return stopped;
    }

    /**
     * At close, with the dispatchers stopped: closes the gates and stops the components in reverse
     * registration order; the jobs still waiting at a gate go to {@code discard}.
     */
    void closeAll(Consumer<Job> discard) {
        List<LocalShell> reverse = new ArrayList<>(shells).reversed();
        for (LocalShell shell : reverse) {
            for (Job job : shell.closeGate()) {
                discard.accept(job);
            }
            shell.stopForClose();
        }
    }

    /** Takes a relocating component off the list; its profile stays until the relocation switches it. */
    void detach(LocalShell shell) {
        shells.remove(shell);
    }

    /**
     * A component was removed or moved away: keeps its counters in the node's totals and lets it
     * go, so that a node through which components keep moving does not keep every shell.
     */
    void retire(LocalShell shell) {
        synchronized (retiredCounts) {
            if (everAdded.remove(shell)) {
                retiredCounts[0] += shell.handledCount();
                retiredCounts[1] += shell.failedCount();
                retiredCounts[2] += shell.restartCount();
            }
        }
    }

    /** The counters of every component hosted so far, retired ones included. */
    Totals totals() {
        long handled;
        long failed;
        long restarts;
        synchronized (retiredCounts) {
            handled = retiredCounts[0];
            failed = retiredCounts[1];
            restarts = retiredCounts[2];
            for (LocalShell shell : everAdded) {
                handled += shell.handledCount();
                failed += shell.failedCount();
                restarts += shell.restartCount();
            }
        }
        return new Totals(handled, failed, restarts);
    }

    /**
     * The local component {@code profile} resolves to.
     *
     * @throws IllegalArgumentException if it is hosted on another node
     */
    LocalShell local(Profile profile) {
        Endpoint endpoint = registry.resolve(Objects.requireNonNull(profile, "profile"));
        if (endpoint instanceof Endpoint.Local local) {
            return (LocalShell) local.shell();
        }
        throw new IllegalArgumentException("profile '" + profile + "' is hosted on another node; manage it there");
    }

    /**
     * The ordering of the migrated component that arrived as {@code arrival}.
     *
     * @throws IllegalArgumentException if no migrated component arrived so
     */
    ArrivalPen arrivedAs(Profile arrival) {
        Endpoint endpoint = registry.lookup(Objects.requireNonNull(arrival, "arrival"));
        if (!(endpoint instanceof Endpoint.Local local) || local.shell().profile().equals(arrival)) {
            throw new IllegalArgumentException("no migrated component arrived as '" + arrival + "'");
        }
        ArrivalPen pen = ((LocalShell) local.shell()).pen();
        if (pen == null) {
            throw new IllegalArgumentException("'" + local.shell().profile() + "' did not arrive by migration");
        }
        return pen;
    }
}
