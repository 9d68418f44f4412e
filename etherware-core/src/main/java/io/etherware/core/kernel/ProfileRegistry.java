package io.etherware.core.kernel;

import io.etherware.core.message.Profile;
import java.util.Set;

/**
 * The node's naming service (paper Section III-C): which endpoint each profile stands for.
 *
 * <p>A profile resolves by exact match first; otherwise it is a query (a role plus a subset of
 * attributes, see {@link Profile#matches}) that must match exactly one registered profile.
 * Local components are registered by the node when they are added; transports register
 * {@link RemoteRoute}s for profiles hosted elsewhere. A local component added under a profile
 * that a remote route holds displaces the route (the local component wins; the transport learns
 * of it through its {@link Listener}).
 *
 * <p>Thread-safety: reads are lock-free (the kernel resolves on every send); registrations are
 * serialized and become visible to all threads at once.
 */
public interface ProfileRegistry {

    /**
     * The endpoint for {@code profile}. Lock-free.
     *
     * @param profile an exact profile, or a query that must match exactly one registered profile
     * @return the local component or the remote route it stands for
     * @throws ProfileResolutionException if nothing matches or a query matches several profiles;
     *                                    the message names the candidates
     */
    Endpoint resolve(Profile profile);

    /** {@return the registered profiles, local and remote: an unmodifiable copy taken now} */
    Set<Profile> profiles();

    /**
     * Registers a route to a profile hosted on another node.
     *
     * @param profile the exact profile of the remote component
     * @param route   the transport's way to it
     * @throws IllegalArgumentException if the profile is already registered
     */
    void registerRemote(Profile profile, RemoteRoute route);

    /**
     * Removes a remote route.
     *
     * @param profile the exact profile the route was registered for
     * @return whether a remote route was registered for the profile
     * @throws IllegalArgumentException if the profile belongs to a local component
     */
    boolean unregisterRemote(Profile profile);

    /**
     * Points {@code profile} from one remote route to another in one step, so that no send in
     * between finds it unregistered (a transport takes over the route a migration left at its
     * source).
     *
     * @param profile     the exact profile
     * @param expected    the route that must be registered for it now
     * @param replacement the route it is registered for from now on
     * @return whether {@code expected} was registered for it (and was replaced); false changes nothing
     */
    boolean replaceRemote(Profile profile, RemoteRoute expected, RemoteRoute replacement);

    /**
     * Adds a listener told of every later change of the registry. A transport uses it to announce
     * the profiles its node hosts when they change.
     *
     * @param listener told of each change from now on, on the thread that makes it
     */
    void addListener(Listener listener);

    /**
     * Removes a listener; it is told of no change after this returns.
     *
     * @param listener a listener given to {@link #addListener}
     * @return whether it was registered
     */
    boolean removeListener(Listener listener);

    /**
     * Told of each change of the registry: a profile registered ({@code before} null), removed
     * ({@code after} null) or pointed at another endpoint (a relocation, a local component
     * displacing a remote route).
     *
     * <p>Threading contract: called on the thread that made the change, after it took effect and
     * while changes are still serialized, so calls come one at a time in the order of the
     * changes. It must not block and must not change the registry itself: hand work to another
     * thread. An exception it throws is logged and does not undo the change.
     */
    @FunctionalInterface
    interface Listener {

        /**
         * {@code profile} went from {@code before} to {@code after}.
         *
         * @param profile the exact profile that changed
         * @param before  its endpoint until now, or null if it was not registered
         * @param after   its endpoint from now on, or null if it was removed
         */
        void onChanged(Profile profile, Endpoint before, Endpoint after);
    }
}
