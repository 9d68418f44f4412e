package io.etherware.core.kernel.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.message.Profile;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

class ProfileTableTest {

    private static Endpoint.Remote route() {
        return new Endpoint.Remote(message -> { });
    }

    @Test
    void shouldPreferTheExactProfileWhenAQueryWouldAlsoMatchOthers() {
        var table = new ProfileTable();
        var exact = route();
        table.register(Profile.of("controller", "car", "1"), exact);
        table.register(Profile.of("controller", "car", "1", "mode", "safe"), route());
        assertSame(exact, table.lookup(Profile.of("controller", "car", "1")));
        assertNull(table.lookup(Profile.of("controller")), "two match the bare role");
    }

    @Test
    void shouldForgetCachedQueriesWhenTheTableChanges() {
        var table = new ProfileTable();
        var first = route();
        table.register(Profile.of("controller", "car", "1"), first);
        Profile query = Profile.of("controller");
        assertSame(first, table.lookup(query)); // now cached
        table.register(Profile.of("controller", "car", "2"), route());
        assertNull(table.lookup(query), "the cached answer must not survive a registration");
        var error = assertThrows(ProfileResolutionException.class, () -> table.resolve(query));
        assertEquals(List.of(Profile.of("controller", "car", "1"), Profile.of("controller", "car", "2")),
                error.candidates());
        assertTrue(table.unregister(Profile.of("controller", "car", "2"), table.lookup(Profile.of("controller", "car", "2"))));
        assertSame(first, table.lookup(query));
    }

    @Test
    void shouldReplaceOnlyTheExpectedEndpoint() {
        var table = new ProfileTable();
        var old = route();
        var replacement = route();
        Profile profile = Profile.of("x");
        table.register(profile, old);
        assertFalse(table.replace(profile, replacement, old), "not the current endpoint");
        assertTrue(table.replace(profile, old, replacement));
        assertSame(replacement, table.resolve(profile));
    }

    @Test
    void shouldExplainANoMatchWithTheProfile() {
        var table = new ProfileTable();
        var error = assertThrows(ProfileResolutionException.class, () -> table.resolve(Profile.of("ghost")));
        assertEquals("no component matches profile 'ghost'", error.getMessage());
        assertTrue(error.candidates().isEmpty());
    }

    @Test
    void shouldResolveWithoutErrorsWhileAnotherThreadRegisters() throws Exception {
        var table = new ProfileTable();
        var stable = route();
        table.register(Profile.of("stable"), stable);
        Thread writer = Thread.ofPlatform().start(() -> {
            for (int i = 0; i < 2_000; i++) {
                table.register(Profile.of("churn", "i", Integer.toString(i)), route());
            }
        });
        long misses = 0;
        while (writer.isAlive()) {
            if (table.lookup(Profile.of("stable")) != stable) {
                misses++;
            }
        }
        writer.join();
        assertEquals(0, misses);
        assertEquals(2_001, table.profiles().size());
    }

    /** One change as a listener saw it. */
    private record Change(Profile profile, Endpoint before, Endpoint after) {
    }

    @Test
    void shouldTellListenersOfEachChangeInOrder() {
        var table = new ProfileTable();
        var changes = new ArrayList<Change>();
        table.addListener((profile, before, after) -> changes.add(new Change(profile, before, after)));
        Profile x = Profile.of("x");
        var first = route();
        var second = route();
        table.register(x, first);
        assertTrue(table.replace(x, first, second));
        assertFalse(table.replace(x, first, second), "a refused replace is no change");
        assertTrue(table.unregister(x, second));
        assertEquals(List.of(new Change(x, null, first), new Change(x, first, second), new Change(x, second, null)),
                changes);
    }

    @Test
    void shouldKeepChangingWhenAListenerThrowsAndStopTellingARemovedListener() {
        var table = new ProfileTable();
        var told = new ArrayList<Profile>();
        ProfileTable.Listener failing = (profile, before, after) -> {
            throw new IllegalStateException("listener bug");
        };
        ProfileTable.Listener recording = (profile, before, after) -> told.add(profile);
        table.addListener(failing);
        table.addListener(recording);
        table.register(Profile.of("a"), route());
        assertNotNull(table.lookup(Profile.of("a")), "the change stands despite the failing listener");
        assertTrue(table.removeListener(recording));
        assertFalse(table.removeListener(recording));
        table.register(Profile.of("b"), route());
        assertEquals(List.of(Profile.of("a")), told);
    }
}
