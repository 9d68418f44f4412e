package io.etherware.deploy.internal;

import io.etherware.deploy.DeploymentException;
import java.io.IOException;
import java.io.StringReader;
import java.net.URL;
import java.nio.charset.CharacterCodingException;
import java.nio.charset.CodingErrorAction;
import java.nio.charset.StandardCharsets;
import java.nio.ByteBuffer;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Deque;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import javax.xml.XMLConstants;
import javax.xml.parsers.ParserConfigurationException;
import javax.xml.parsers.SAXParserFactory;
import javax.xml.validation.Schema;
import javax.xml.validation.SchemaFactory;
import org.xml.sax.Attributes;
import org.xml.sax.ErrorHandler;
import org.xml.sax.InputSource;
import org.xml.sax.Locator;
import org.xml.sax.SAXException;
import org.xml.sax.SAXParseException;
import org.xml.sax.helpers.DefaultHandler;

/**
 * Reads a deployment file into {@link XmlElement}s: replaces {@code ${name}} and
 * {@code ${name:-default}} in it with the given properties, then parses it with the JDK's parser,
 * validating against {@code etherware-deployment.xsd} as it goes, with DOCTYPEs refused (no
 * external entities, no entity expansion). The first problem ends the read with a
 * {@link DeploymentException} naming the line, the element and, for the schema's own types, the fix.
 * Stateless apart from the compiled schema; thread-safe.
 */
public final class XmlReader {

    /** The schema, on the class path beside {@link io.etherware.deploy.DeploymentReader}. */
    public static final String SCHEMA_RESOURCE = "/io/etherware/deploy/etherware-deployment.xsd";
    /** Largest deployment file read: 1 MiB. */
    public static final int MAX_FILE_BYTES = 1 << 20;

    private static final Pattern PROPERTY = Pattern.compile("\\$\\{([A-Za-z0-9_.-]+)(?::-([^}]*))?}");
    /** The fix for a value that is not of one of the schema's simple types, by type name. */
    private static final Map<String, String> FIXES = Map.ofEntries(
            Map.entry("DurationText", "write a number and a unit (ns, us, ms, s, min), e.g. 15ms"),
            Map.entry("HostPort", "write HOST:PORT, e.g. 127.0.0.1:7400"),
            Map.entry("ProfileText", "write a role or role[key=value,...], e.g. controller[pendulum=1]"),
            Map.entry("CpuList", "write CPU numbers and ranges, e.g. 1 or 0,2-3"),
            Map.entry("Name", "use letters, digits, '_', '.' and '-', starting with a letter, digit or '_'"),
            Map.entry("ClassName", "write a fully qualified Java class name, e.g. com.example.MyFactory"),
            Map.entry("NodePattern", "write a node id or *"),
            Map.entry("Lanes", "write 1 or 2 (every node of a deployment the same)"),
            Map.entry("OperationList", "write UPGRADE, MIGRATE or both, separated by a space"));

    private final Schema schema;

    /** A reader with the deployment schema compiled. */
    public XmlReader() {
        URL resource = Objects.requireNonNull(XmlReader.class.getResource(SCHEMA_RESOURCE), SCHEMA_RESOURCE);
        try {
            SchemaFactory factory = SchemaFactory.newDefaultInstance();
            factory.setFeature(XMLConstants.FEATURE_SECURE_PROCESSING, true);
            schema = factory.newSchema(resource);
        } catch (SAXException e) {
            throw new IllegalStateException("the packaged " + SCHEMA_RESOURCE + " does not compile", e);
        }
    }

    /**
     * Reads and validates {@code file}.
     *
     * @param file       the deployment file
     * @param properties values for {@code ${name}} in it
     * @return its root element
     * @throws DeploymentException naming the place and the problem: unreadable, too large, not
     *                             UTF-8, an undefined property, not well-formed, or not valid
     */
    public XmlElement read(Path file, Map<String, String> properties) throws DeploymentException {
        byte[] bytes;
        try {
            if (Files.size(file) > MAX_FILE_BYTES) {
                throw new DeploymentException(file, 0, 0, "the file has " + Files.size(file) + " bytes, more than a"
                        + " deployment's limit of " + MAX_FILE_BYTES + "; is it the right file?", null);
            }
            bytes = Files.readAllBytes(file);
        } catch (IOException e) {
            throw new DeploymentException(file, 0, 0, "cannot be read (" + e + "); check the path", e);
        }
        String text;
        try {
            text = StandardCharsets.UTF_8.newDecoder().onMalformedInput(CodingErrorAction.REPORT)
                    .onUnmappableCharacter(CodingErrorAction.REPORT).decode(ByteBuffer.wrap(bytes)).toString();
        } catch (CharacterCodingException e) {
            throw new DeploymentException(file, 0, 0, "is not UTF-8 text (" + e.getMessage() + "); save it as UTF-8",
                    e);
        }
        if (text.startsWith("\uFEFF")) {
            text = text.substring(1); // a byte order mark, as some editors write
        }
        return parse(file, substitute(file, text, properties));
    }

    /**
     * Replaces each {@code ${name}} outside comments, line by line so that lines keep their
     * numbers: a {@code -P} value is escaped as XML text, a default written in the file is taken
     * as written. A {@code -P} name the file never uses is refused, as a misspelt one would
     * otherwise pass silently as its default.
     */
    static String substitute(Path file, String text, Map<String, String> properties) throws DeploymentException {
        String[] lines = text.split("\n", -1);
        var out = new StringBuilder(text.length());
        var used = new java.util.HashSet<String>();
        boolean inComment = false;
        for (int i = 0; i < lines.length; i++) {
            var line = new StringBuilder();
            String rest = lines[i];
            while (!rest.isEmpty()) {
                if (inComment) {
                    int end = rest.indexOf("-->");
                    int upTo = end < 0 ? rest.length() : end + 3;
                    line.append(rest, 0, upTo);
                    rest = rest.substring(upTo);
                    inComment = end < 0;
                    continue;
                }
                int start = rest.indexOf("<!--");
                String part = start < 0 ? rest : rest.substring(0, start);
                Matcher matcher = PROPERTY.matcher(part);
                while (matcher.find()) {
                    String name = matcher.group(1);
                    used.add(name);
                    String value = properties.containsKey(name) ? escape(properties.get(name)) : matcher.group(2);
                    if (value == null) {
                        throw new DeploymentException(file, i + 1, line.length() + matcher.start() + 1, "${" + name
                                + "} is not defined: pass -P " + name + "=VALUE to the launcher, or write ${" + name
                                + ":-DEFAULT}", null);
                    }
                    matcher.appendReplacement(line, Matcher.quoteReplacement(value));
                }
                matcher.appendTail(line);
                rest = start < 0 ? "" : rest.substring(start);
                inComment = start >= 0;
                if (inComment) {
                    line.append("<!--");
                    rest = rest.substring(4);
                }
            }
            out.append(line);
            if (i < lines.length - 1) {
                out.append('\n');
            }
        }
        var unused = new java.util.TreeSet<>(properties.keySet());
        unused.removeAll(used);
        if (!unused.isEmpty()) {
            throw new DeploymentException(file, 0, 0, "-P " + String.join(", -P ", unused) + ": the file has no ${"
                    + unused.first() + "}; it uses " + (used.isEmpty() ? "no properties" : new java.util.TreeSet<>(used))
                    + " (check the spelling)", null);
        }
        return out.toString();
    }

    private static String escape(String value) {
        return value.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace("\"", "&quot;")
                .replace("'", "&apos;").replace("\n", "&#10;");
    }

    private XmlElement parse(Path file, String text) throws DeploymentException {
        var handler = new TreeBuilder(file);
        try {
            SAXParserFactory factory = SAXParserFactory.newDefaultNSInstance();
            factory.setFeature(XMLConstants.FEATURE_SECURE_PROCESSING, true);
            factory.setFeature("http://apache.org/xml/features/disallow-doctype-decl", true);
            factory.setXIncludeAware(false);
            factory.setSchema(schema);
            var reader = factory.newSAXParser().getXMLReader();
            reader.setContentHandler(handler);
            reader.setErrorHandler(handler);
            reader.parse(new InputSource(new StringReader(text)));
        } catch (SAXParseException e) {
            throw handler.problem(e);
        } catch (SAXException | ParserConfigurationException e) {
            throw new DeploymentException(file, 0, 0, "cannot be parsed: " + e.getMessage(), e);
        } catch (IOException e) {
            throw new DeploymentException(file, 0, 0, "cannot be read: " + e, e);
        }
        return handler.root;
    }

    /** Builds the tree; turns the parser's first error into the launcher's message. */
    private static final class TreeBuilder extends DefaultHandler implements ErrorHandler {
        private final Path file;
        private final Deque<Open> open = new ArrayDeque<>();
        private Locator locator;
        private XmlElement root;
        /** A value's error waiting for the one that names its attribute and element. */
        private SAXParseException held;

        TreeBuilder(Path file) {
            this.file = file;
        }

        @Override
        public void setDocumentLocator(Locator value) {
            locator = value;
        }

        @Override
        public void startElement(String uri, String localName, String qName, Attributes attributes) {
            var values = new LinkedHashMap<String, String>();
            for (int i = 0; i < attributes.getLength(); i++) {
                values.put(attributes.getQName(i), attributes.getValue(i));
            }
            open.push(new Open(qName, values, new ArrayList<>(), locator.getLineNumber(), locator.getColumnNumber()));
        }

        @Override
        public void endElement(String uri, String localName, String qName) {
            Open element = open.pop();
            var done = new XmlElement(element.name, element.attributes, element.children, element.line,
                    element.column);
            if (open.isEmpty()) {
                root = done;
            } else {
                open.peek().children.add(done);
            }
        }

        @Override
        public void warning(SAXParseException e) {
            // the schema's warnings do not stop a deployment
        }

        @Override
        public void error(SAXParseException e) throws SAXException {
            // The schema validator reports a bad value twice: first what the value breaks (a
            // pattern, a range), then which attribute of which element holds it. Keep the first
            // for its detail and throw at the second, which names the place.
            if (held == null && e.getMessage() != null && e.getMessage().matches("cvc-[a-zA-Z]+-valid:.*")) {
                held = e;
                return;
            }
            throw e;
        }

        @Override
        public void endDocument() throws SAXException {
            if (held != null) {
                throw held;
            }
        }

        @Override
        public void fatalError(SAXParseException e) throws SAXException {
            throw e;
        }

        DeploymentException problem(SAXParseException e) {
            String message = sentence(e);
            if (held != null && held != e) {
                message = message + " (" + sentence(held) + ")";
            }
            // The validator's messages about attributes and elements name the element themselves.
            String where = open.isEmpty() || message.contains("element '") ? ""
                    : "inside <" + open.peek().name + ">: ";
            String fix = message.startsWith("cvc-") ? "; see etherware-deployment.xsd"
                    : "; the file must be well-formed XML";
            for (var entry : FIXES.entrySet()) {
                if (message.contains("'" + entry.getKey() + "'")) {
                    fix = "; " + entry.getValue();
                }
            }
            return new DeploymentException(file, e.getLineNumber(), e.getColumnNumber(), where + message + fix, e);
        }

        private static String sentence(SAXParseException e) {
            String message = e.getMessage() == null ? e.toString() : e.getMessage().strip();
            return message.endsWith(".") ? message.substring(0, message.length() - 1) : message;
        }
    }

    private record Open(String name, Map<String, String> attributes, List<XmlElement> children, int line,
                        int column) {
    }
}
