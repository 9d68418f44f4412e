package io.etherware.examples;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.stream.Stream;
import org.junit.jupiter.api.Test;

/**
 * The README's Java examples are the code that runs them: every {@code java} block of the README
 * appears, line for line and in order, between a {@code // README example begins} and {@code ends}
 * marker in a test, or in the complete program ({@code examples/.../quickstart/QuickStart.java},
 * run by {@code QuickStartIT}); a marked region may add only assertions, so neither can change
 * without the other.
 */
class ReadmeExamplesTest {

    private static final Path ROOT = Path.of("..");
    private static final String BEGINS = "// README example begins";
    private static final String ENDS = "// README example ends";

    @Test
    void shouldFindEveryReadmeJavaBlockInATestThatRunsIt() throws IOException {
        List<List<String>> blocks = javaBlocks(Files.readAllLines(ROOT.resolve("README.md")));
        List<Path> tests = markedTests();
        assertTrue(blocks.size() >= 4 && tests.size() >= 4, blocks.size() + " README blocks, " + tests.size() + " tests");

        List<List<String>> unmatched = new ArrayList<>(blocks);
        for (Path test : tests) {
            List<String> file = significant(Files.readAllLines(test));
            for (List<String> region : markedRegions(file)) {
                List<String> marked = region.stream().filter(line -> !line.startsWith("assert")).toList();
                boolean found = unmatched.removeIf(block -> isSubsequence(block, region) && isSubsequence(marked, block));
                assertTrue(found, test + ": its README example (" + marked.getFirst() + " ...) is not in the README as it is");
            }
        }
        assertEquals(List.of(), unmatched, "README java blocks that no test runs");
    }

    private static List<List<String>> javaBlocks(List<String> readme) {
        List<List<String>> blocks = new ArrayList<>();
        List<String> current = null;
        for (String line : readme) {
            if (current == null && line.strip().equals("```java")) {
                current = new ArrayList<>();
            } else if (current != null && line.strip().equals("```")) {
                blocks.add(significant(current));
                current = null;
            } else if (current != null) {
                current.add(line);
            }
        }
        return blocks;
    }

    /** Each region between a begins and an ends marker, with its assertions. */
    private static List<List<String>> markedRegions(List<String> file) {
        List<List<String>> regions = new ArrayList<>();
        int from = file.indexOf(BEGINS);
        while (from >= 0) {
            int to = file.subList(from, file.size()).indexOf(ENDS) + from;
            assertTrue(to > from, "a README example begins without an end");
            regions.add(file.subList(from + 1, to));
            int next = file.subList(to, file.size()).indexOf(BEGINS);
            from = next < 0 ? -1 : next + to;
        }
        return regions;
    }

    private static List<Path> markedTests() throws IOException {
        List<Path> tests = new ArrayList<>();
        for (String module : List.of("etherware-core/src/test/java", "etherware-rt/src/test/java",
                "etherware-services/src/test/java", "pendulum-sim/src/test/java", "examples/src/test/java",
                "examples/src/main/java/io/etherware/examples/quickstart")) {
            Path sources = ROOT.resolve(module);
            if (!Files.isDirectory(sources)) {
                continue;
            }
            try (Stream<Path> files = Files.walk(sources)) {
                for (Path file : files.filter(f -> f.toString().endsWith(".java")).toList()) {
                    if (!file.endsWith("ReadmeExamplesTest.java") && Files.readString(file).contains(BEGINS)) {
                        tests.add(file);
                    }
                }
            }
        }
        return tests;
    }

    /** Lines stripped of indentation, blank ones dropped. */
    private static List<String> significant(List<String> lines) {
        return lines.stream().map(String::strip).filter(line -> !line.isEmpty()).toList();
    }

    private static boolean isSubsequence(List<String> part, List<String> whole) {
        int at = 0;
        for (String line : whole) {
            if (at < part.size() && part.get(at).equals(line)) {
                at++;
            }
        }
        return at == part.size();
    }
}
