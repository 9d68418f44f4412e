package io.etherware.core.codec.internal;

import io.etherware.core.message.Profile;

import java.util.concurrent.ConcurrentHashMap;

/**
 * Parsed envelope profiles by their text. A node talks to few profiles, and parsing one
 * (validation by regular expressions, an ordered map) costs more than the rest of the envelope,
 * so each codec remembers the ones it has seen.
 *
 * <p>Bounded against a peer sending ever new profiles: only short texts are kept, and the cache
 * is emptied when full. Profiles are immutable, so sharing them is safe. Thread-safe, lock-free
 * on hits.
 */
final class ProfileCache {

    static final int MAX_ENTRIES = 1024;
    static final int MAX_CACHED_TEXT_LENGTH = 256;

    private final ConcurrentHashMap<String, Profile> byText = new ConcurrentHashMap<>();

    /**
     * The profile with this text form.
     *
     * @throws IllegalArgumentException from {@link Profile#parse} if the text is malformed
     */
    Profile parse(String text) {
        Profile profile = byText.get(text);
        if (profile != null) {
            return profile;
        }
        profile = Profile.parse(text);
        if (text.length() <= MAX_CACHED_TEXT_LENGTH) {
            if (byText.size() >= MAX_ENTRIES) {
                byText.clear();
            }
            byText.put(text, profile);
        }
        return profile;
    }

    int size() {
        return byText.size();
    }
}
