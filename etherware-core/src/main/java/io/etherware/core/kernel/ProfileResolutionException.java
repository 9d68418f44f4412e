package io.etherware.core.kernel;

import io.etherware.core.message.Profile;
import java.util.List;

/**
 * A profile did not resolve to exactly one endpoint: nothing matches it, or a query matches
 * several. The message names the profile and the candidates.
 */
public final class ProfileResolutionException extends RuntimeException {

    private final Profile profile;
    private final List<Profile> candidates;

    public ProfileResolutionException(Profile profile, List<Profile> candidates, String message) {
        super(message);
        this.profile = profile;
        this.candidates = List.copyOf(candidates);
    }

    /** The profile or query that did not resolve. */
    public Profile profile() {
        return profile;
    }

    /** The registered profiles that match it: empty for no match, several when ambiguous. */
    public List<Profile> candidates() {
        return candidates;
    }
}
