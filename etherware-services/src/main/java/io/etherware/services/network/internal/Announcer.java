package io.etherware.services.network.internal;

import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.ProfileRegistry;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.message.Profile;
import java.util.ArrayList;
import java.util.Collection;
import java.util.Comparator;
import java.util.List;
import java.util.Queue;
import java.util.TreeSet;

/**
 * This node's side of location transparency: follows the registry and announces the profiles
 * hosted here (the node's own profile and every local component) to every connected peer,
 * whenever they change. The announcement travels ahead of any message sent after the change,
 * so a peer can always route the reply to a request.
 *
 * <p>Thread-safety: the registry calls {@link #onChanged} within its serialized changes; the
 * announced set is guarded by this object; lock order is registry, this, then a link's lock.
 */
final class Announcer implements ProfileRegistry.Listener {

    private final Kernel kernel;
    private final Collection<Peer> peers;
    private final Queue<Profile> toReconcile;
    // Guarded by this.
    private final TreeSet<Profile> localProfiles = new TreeSet<>(Comparator.comparing(Profile::toString));
    private long version;
    private volatile byte[] body;

    /**
     * @param peers       the messenger's peers, a live view
     * @param toReconcile where to put profiles whose remote route the route table must settle
     *                    (it cannot be called from within a registry change)
     */
    Announcer(Kernel kernel, Collection<Peer> peers, Queue<Profile> toReconcile) {
        this.kernel = kernel;
        this.peers = peers;
        this.toReconcile = toReconcile;
        this.body = FrameWriter.announceBody(0, List.of(kernel.profile()));
    }

    /** Starts following the registry, from the profiles registered now. */
    void start() {
        kernel.registry().addListener(this);
        synchronized (this) {
            for (Profile profile : kernel.registry().profiles()) {
                if (isLocal(profile)) {
                    localProfiles.add(profile);
                }
            }
            publish();
        }
    }

    void stop() {
        kernel.registry().removeListener(this);
    }

    /** The current ANNOUNCE body, for a connection that opens. */
    byte[] body() {
        return body;
    }

    @Override
    public void onChanged(Profile profile, Endpoint before, Endpoint after) {
        boolean wasLocal = hosts(profile, before);
        boolean isLocal = hosts(profile, after);
        if (before instanceof Endpoint.Remote was && was.route() instanceof RouteTable.ProfileRoute
                && !(after instanceof Endpoint.Remote now && now.route() == was.route())
                || wasLocal && after == null) {
            // A route of ours was displaced, or a local component left while a peer may announce
            // its profile: the control thread settles it.
            toReconcile.add(profile);
        }
        if (wasLocal == isLocal) {
            return;
        }
        synchronized (this) {
            if (isLocal) {
                localProfiles.add(profile);
            } else {
                localProfiles.remove(profile);
            }
            publish();
        }
    }

    /** Hands the full set to every connected peer's writer (replacing one not yet written). */
    private void publish() {
        var all = new ArrayList<Profile>(localProfiles.size() + 1);
        all.add(kernel.profile());
        all.addAll(localProfiles);
        byte[] next = FrameWriter.announceBody(++version, all);
        body = next;
        for (Peer peer : peers) {
            // Every lane: each carries the announcement ahead of its own later messages.
            for (Link link : peer.links()) {
                link.lock.lock();
                try {
                    Connection active = link.active();
                    if (active != null) {
                        active.requests.announce(next);
                        link.work.signal();
                    }
                } finally {
                    link.lock.unlock();
                }
            }
        }
    }

    private boolean isLocal(Profile profile) {
        try {
            return hosts(profile, kernel.registry().resolve(profile));
        } catch (ProfileResolutionException e) {
            return false;
        }
    }

    /**
     * Whether {@code endpoint} is a local component registered under its own profile. A second
     * profile of a local component (a migration's arrival profile, which only its source sends
     * to, through a route to this node) is not announced.
     */
    private static boolean hosts(Profile profile, Endpoint endpoint) {
        return endpoint instanceof Endpoint.Local local && local.shell().profile().equals(profile);
    }
}
