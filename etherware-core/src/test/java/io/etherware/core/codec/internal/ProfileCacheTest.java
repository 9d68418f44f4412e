package io.etherware.core.codec.internal;

import io.etherware.core.message.Profile;
import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class ProfileCacheTest {

    private final ProfileCache cache = new ProfileCache();

    @Test
    void shouldReturnTheSameProfileWhenTheTextRepeats() {
        Profile first = cache.parse("controller[car=1]");
        assertEquals(Profile.parse("controller[car=1]"), first);
        assertSame(first, cache.parse("controller[car=1]"));
    }

    @Test
    void shouldStayBoundedWhenEveryProfileIsNew() {
        for (int i = 0; i < 10 * ProfileCache.MAX_ENTRIES; i++) {
            assertEquals("c[n=" + i + "]", cache.parse("c[n=" + i + "]").toString());
            assertTrue(cache.size() <= ProfileCache.MAX_ENTRIES, "size " + cache.size());
        }
    }

    @Test
    void shouldNotKeepLongTexts() {
        String role = "r".repeat(ProfileCache.MAX_CACHED_TEXT_LENGTH + 1);
        assertEquals(role, cache.parse(role).role());
        assertEquals(0, cache.size());
    }

    @Test
    void shouldRejectMalformedTextEveryTime() {
        assertThrows(IllegalArgumentException.class, () -> cache.parse("controller[car"));
        assertThrows(IllegalArgumentException.class, () -> cache.parse("controller[car"));
        assertEquals(0, cache.size());
    }
}
