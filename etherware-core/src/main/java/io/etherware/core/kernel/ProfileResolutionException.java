package io.etherware.core.kernel;

import io.etherware.core.message.Profile;
import java.util.List;

/**
 * A profile did not resolve to exactly one endpoint: nothing matches it, or a query matches
 * several. The message names the profile and the candidates.
 */
public final class ProfileResolutionException extends RuntimeException {

    /** The profile or query that did not resolve. */
    private final Profile profile;
    /** The registered profiles that match it, an unmodifiable copy. */
    private final List<Profile> candidates;

    /**
     * A resolution failure.
     *
     * @param profile    the profile or query that did not resolve
     * @param candidates the registered profiles that match it: empty for no match, several when
     *                   ambiguous; copied
     * @param message    the text for logs, naming the profile and the candidates
     */
    public ProfileResolutionException(Profile profile, List<Profile> candidates, String message) {
        super(message);
        this.profile = profile;
        this.candidates = List.copyOf(candidates);
    }

    /** {@return the profile or query that did not resolve} */
    public Profile profile() {
        return profile;
    }

    /**
     * {@return the registered profiles that match it: empty for no match, several when ambiguous}
     */
    public List<Profile> candidates() {
        return candidates;
    }
}
