package io.etherware.services.network;

import io.etherware.core.message.Profile;
import io.etherware.services.time.PeerTime;
import java.util.Optional;
import java.util.Set;

/**
 * One peer as a {@link NetworkMessenger} sees it now.
 *
 * <p>Immutable; a snapshot.
 *
 * @param nodeId    the peer's node id
 * @param connected whether a connection is up
 * @param remote    the address of the connection in use, or empty
 * @param queued    messages waiting to be written to it
 * @param inFlight  messages written and not yet acknowledged by its kernel
 * @param profiles  the profiles it announced that this node routes to it
 * @param time      what NetworkTime knows of its clock
 */
public record PeerStatus(String nodeId, boolean connected, Optional<String> remote, int queued, int inFlight,
                         Set<Profile> profiles, Optional<PeerTime> time) {

    /**
     * Copies {@code profiles}.
     *
     * @throws NullPointerException if {@code profiles} is null or holds null
     */
    public PeerStatus {
        profiles = Set.copyOf(profiles);
    }
}
