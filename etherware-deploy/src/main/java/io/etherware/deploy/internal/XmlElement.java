package io.etherware.deploy.internal;

import java.util.List;
import java.util.Map;
import java.util.Optional;

/**
 * One element of a deployment file as read: its name, attributes (defaults of the schema filled
 * in), children and where it starts, for errors that name the line. Immutable.
 *
 * @param name       the element's name
 * @param attributes its attributes by name, in document order
 * @param children   its child elements, in document order
 * @param line       the line its start tag ends on (1-based), as the XML parser reports it
 * @param column     the column there
 */
public record XmlElement(String name, Map<String, String> attributes, List<XmlElement> children, int line,
                         int column) {

    public XmlElement {
        attributes = Map.copyOf(attributes);
        children = List.copyOf(children);
    }

    /**
     * The value of attribute {@code attribute}, if present.
     *
     * @param attribute its name
     * @return the value, or empty
     */
    public Optional<String> attribute(String attribute) {
        return Optional.ofNullable(attributes.get(attribute));
    }

    /**
     * The children named {@code childName}, in document order.
     *
     * @param childName the element name
     * @return those children, possibly none
     */
    public List<XmlElement> children(String childName) {
        return children.stream().filter(child -> child.name.equals(childName)).toList();
    }

    /**
     * The first child named {@code childName}, if any.
     *
     * @param childName the element name
     * @return the child, or empty
     */
    public Optional<XmlElement> child(String childName) {
        return children.stream().filter(child -> child.name.equals(childName)).findFirst();
    }
}
