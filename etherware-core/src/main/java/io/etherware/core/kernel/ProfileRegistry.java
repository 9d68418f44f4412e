package io.etherware.core.kernel;

import io.etherware.core.message.Profile;
import java.util.Set;

/**
 * The node's naming service (paper Section III-C): which endpoint each profile stands for.
 *
 * <p>A profile resolves by exact match first; otherwise it is a query (a role plus a subset of
 * attributes, see {@link Profile#matches}) that must match exactly one registered profile.
 * Local components are registered by the node when they are added; transports register
 * {@link RemoteRoute}s for profiles hosted elsewhere.
 *
 * <p>Thread-safety: reads are lock-free (the kernel resolves on every send); registrations are
 * serialized and become visible to all threads at once.
 */
public interface ProfileRegistry {

    /**
     * The endpoint for {@code profile}.
     *
     * @throws ProfileResolutionException if nothing matches or a query matches several profiles;
     *                                    the message names the candidates
     */
    Endpoint resolve(Profile profile);

    /** The registered profiles, local and remote. */
    Set<Profile> profiles();

    /**
     * Registers a route to a profile hosted on another node.
     *
     * @throws IllegalArgumentException if the profile is already registered
     */
    void registerRemote(Profile profile, RemoteRoute route);

    /**
     * Removes a remote route.
     *
     * @return whether a remote route was registered for the profile
     * @throws IllegalArgumentException if the profile belongs to a local component
     */
    boolean unregisterRemote(Profile profile);
}
